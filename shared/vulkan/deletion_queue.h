// Explicit lifetime: whatever is created pushes its own destruction here, and
// flush() runs them newest first, so objects die in the reverse order of
// their creation (a device after its buffers, an instance after its device).
#pragma once
#include <functional>
#include <utility>
#include <vector>

namespace rg {

class DeletionQueue {
public:
    DeletionQueue() = default;
    DeletionQueue(const DeletionQueue&) = delete;
    DeletionQueue& operator=(const DeletionQueue&) = delete;
    ~DeletionQueue() { flush(); }

    void push(std::function<void()> destroy) {
        destroyers_.push_back(std::move(destroy));
    }

    void flush() {
        while (!destroyers_.empty()) {
            auto destroy = std::move(destroyers_.back());
            destroyers_.pop_back();
            destroy();
        }
    }

private:
    std::vector<std::function<void()>> destroyers_;
};

}  // namespace rg
