#include "core/files.h"

#include "core/interrupt.h"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fcntl.h>
#include <filesystem>
#include <sys/stat.h>
#include <unistd.h>

namespace rg {

void requireRegularFile(const std::string& path, const std::string& key) {
    namespace fs = std::filesystem;
    std::error_code error;
    fs::file_status status = fs::status(path, error);
    std::string where = key + ": " + escapeControl(path) + ": ";
    if (error == std::errc::too_many_symbolic_link_levels)
        throw InputError(where + "a loop of symbolic links");
    if (status.type() == fs::file_type::not_found)
        throw InputError(where + "no such file");
    if (error) throw InputError(where + error.message());
    if (status.type() == fs::file_type::directory)
        throw InputError(where + "is a folder, not a file");
    // reading a FIFO waits forever, /dev/zero never ends
    if (status.type() != fs::file_type::regular)
        throw InputError(where + "is not a regular file (a FIFO, a device or a socket)");
}

namespace {
// Outputs may name folders that do not exist yet (--output out/NN.png).
void makeParent(const std::string& path) {
    std::filesystem::path parent = std::filesystem::path(path).parent_path();
    std::error_code ignored;  // a failure shows as "cannot write" below
    if (!parent.empty()) std::filesystem::create_directories(parent, ignored);
}

// All of `bytes`, retrying short writes; errno of the first failure, or 0.
int writeAll(int fd, const void* bytes, size_t size) {
    const char* p = static_cast<const char*>(bytes);
    while (size > 0) {
        ssize_t n = write(fd, p, size);
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) return n < 0 ? errno : ENOSPC;
        p += n;
        size -= size_t(n);
    }
    return 0;
}

[[noreturn]] void cannotWrite(const std::string& path, int error) {
    throw std::runtime_error("cannot write " + escapeControl(path) + ": " +
                             std::strerror(error));
}
}  // namespace

void writeFileAtomically(const std::string& path, const void* bytes, size_t size) {
    makeParent(path);
    struct stat existing {};
    // /dev/null, a FIFO: in place
    if (stat(path.c_str(), &existing) == 0 && !S_ISREG(existing.st_mode)) {
        int fd = open(path.c_str(), O_WRONLY | O_CLOEXEC);
        if (fd < 0) cannotWrite(path, errno);
        int error = writeAll(fd, bytes, size);
        if (close(fd) != 0 && !error) error = errno;
        if (error) cannotWrite(path, error);
        return;
    }
    // same folder: the rename below is atomic
    std::string temp = path + ".partial-XXXXXX";
    int fd = mkstemp(temp.data());
    if (fd < 0) cannotWrite(path, errno);
    setFileInProgress(temp.c_str());
    mode_t mask = umask(0);
    umask(mask);
    int error = fchmod(fd, 0666 & ~mask) != 0 ? errno : 0;  // mkstemp made it 0600
    if (!error) error = writeAll(fd, bytes, size);
    if (close(fd) != 0 && !error) error = errno;  // a full disk often shows only here
    if (!error && std::rename(temp.c_str(), path.c_str()) != 0) error = errno;
    if (error) unlink(temp.c_str());
    setFileInProgress(nullptr);
    if (error) cannotWrite(path, error);
}

std::string escapeControl(const std::string& text) {
    std::string out;
    for (unsigned char c : text) {
        if (c < 0x20 || c == 0x7f) {
            char code[8];
            std::snprintf(code, sizeof code, "\\x%02x", c);
            out += code;
        } else {
            out += char(c);
        }
    }
    return out;
}

std::filesystem::path executableDir() {
    return std::filesystem::read_symlink("/proc/self/exe").parent_path();
}

}  // namespace rg
