// Files in and out, so that nothing is lost or half-written (every chapter):
// an input must be a regular file (a FIFO would block, a device never end);
// an output appears complete or not at all: it is written to a temporary
// file beside it and renamed into place (rename is atomic within a folder),
// so a full disk or a signal leaves the previous file as it was.
#pragma once
#include <cstddef>
#include <filesystem>
#include <stdexcept>
#include <string>

namespace rg {

// Bad input from the user (a scene file, a value): exit code 2, like a bad flag.
struct InputError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

// Throws InputError "<key>: <path>: <why>" unless `path` names a regular
// file (after symbolic links): missing, a folder, a FIFO, a device or a
// loop of links each get their own reason.
void requireRegularFile(const std::string& path, const std::string& key);

// Writes `bytes` to `path` through `path.partial-XXXXXX` and a rename;
// on any failure removes the temporary file and throws, naming the path.
// An existing `path` that is not a regular file (/dev/null, a FIFO) is
// written in place: renaming over it would replace the device.
void writeFileAtomically(const std::string& path, const void* bytes, size_t size);

// The message text with control characters shown as \xNN (a key or path
// with a newline or an escape sequence stays one harmless line).
std::string escapeControl(const std::string& text);

// Folder of the running executable: SPIR-V and assets are found beside it.
std::filesystem::path executableDir();

}  // namespace rg
