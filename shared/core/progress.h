// Progress of long CPU work (the reference at large sizes, big scene files),
// shown on a terminal only: one line on stderr, rewritten in place at most
// five times a second, from the first second on, and erased at the end.
// When stderr is not a terminal (logs, tests, CI) it prints nothing.
#pragma once
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <string>
#include <unistd.h>

namespace rg {

class Progress {
public:
    Progress(std::string what, uint64_t total)
        : what_(std::move(what)), total_(total), start_(std::chrono::steady_clock::now()),
          terminal_(isatty(fileno(stderr)) == 1) {}
    ~Progress() {
        if (shown_) std::fprintf(stderr, "\r%*s\r", int(what_.size()) + 16, "");
    }
    Progress(const Progress&) = delete;
    Progress& operator=(const Progress&) = delete;

    void update(uint64_t done) {
        if (!terminal_ || total_ == 0) return;
        auto now = std::chrono::steady_clock::now();
        if (now - start_ < std::chrono::seconds(1) ||
            now - last_ < std::chrono::milliseconds(200))
            return;
        last_ = now;
        shown_ = true;
        std::fprintf(stderr, "\r%s: %3d %%", what_.c_str(),
                     int(100.0 * double(done) / double(total_)));
        std::fflush(stderr);
    }

private:
    std::string what_;
    uint64_t total_;
    std::chrono::steady_clock::time_point start_, last_{};
    bool terminal_, shown_ = false;
};

}  // namespace rg
