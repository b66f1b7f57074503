#include "viewer/shader_reload.h"

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <functional>
#include <fstream>
#include <regex>
#include <set>
#include <sstream>
#include <vector>

extern char** environ;

namespace rg {

namespace {
using Clock = std::chrono::steady_clock;
namespace fs = std::filesystem;

// Every distinct stage file of the pipeline, in the SBT's order.
std::vector<std::string> stageFiles(const RtShaders& shaders) {
    std::vector<std::string> files{shaders.raygen};
    for (const std::string& m : shaders.miss) files.push_back(m);
    for (const HitGroup& g : shaders.hitGroups)
        for (const std::string& f : {g.closestHit, g.intersection})
            if (!f.empty()) files.push_back(f);
    std::vector<std::string> unique;
    for (const std::string& f : files)
        if (std::find(unique.begin(), unique.end(), f) == unique.end())
            unique.push_back(f);
    return unique;
}

// Runs a program with its output (stdout and stderr) into `log`; returns
// its exit status, or -1 when it could not start. `started` gets its id.
int runLogged(const std::vector<std::string>& args, const fs::path& log,
              const std::function<void(int)>& started) {
    std::vector<char*> argv;
    for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_addopen(&actions, 1, log.c_str(),
                                     O_WRONLY | O_CREAT | O_TRUNC, 0644);
    posix_spawn_file_actions_adddup2(&actions, 1, 2);
    pid_t child = 0;
    int error = posix_spawnp(&child, argv[0], &actions, nullptr, argv.data(), environ);
    posix_spawn_file_actions_destroy(&actions);
    if (error != 0) return -1;
    started(child);
    int status = 0;
    while (waitpid(child, &status, 0) < 0 && errno == EINTR) {
    }
    return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

// The validator's first error, with the source root taken off its path:
// "shaders/04_raygen_miss/raygen.rgen:30: 'radianc' : no such field ...".
std::string firstError(const fs::path& log, const fs::path& root, int status) {
    std::ifstream in(log);
    std::string line, first;
    while (std::getline(in, line)) {
        if (first.empty() && !line.empty()) first = line;
        if (line.rfind("ERROR: ", 0) == 0) {
            first = line.substr(7);
            break;
        }
    }
    if (first.empty()) first = "glslangValidator exited with " + std::to_string(status);
    std::string prefix = root.string() + "/";
    for (size_t at; (at = first.find(prefix)) != std::string::npos;)
        first.erase(at, prefix.size());
    return first.size() > 200 ? first.substr(0, 200) + "..." : first;
}
}  // namespace

fs::path builtSourceRoot() { return RG_SOURCE_DIR; }

ShaderReload::ShaderReload(RtShaders shaders, fs::path sourceRoot)
    : shaders_(std::move(shaders)), root_(std::move(sourceRoot)) {
    work_ = fs::temp_directory_path() / ("rayglass-shaders-" + std::to_string(getpid()));
    seen_ = sourceTimes();
    lastLook_ = Clock::now();
    if (!fs::exists(root_ / "shaders" / shaders_.raygen))
        report("shaders: no source at " + (root_ / "shaders" / shaders_.raygen).string() +
                   " (--shader-source): reload is off",
               false);
}

ShaderReload::~ShaderReload() {
    {
        std::lock_guard lock(mutex_);
        stopping_ = true;
        if (busy_ && child_ > 0) kill(child_, SIGTERM);
    }
    if (worker_.joinable()) worker_.join();
    std::error_code ignored;
    fs::remove_all(work_, ignored);
}

// The stage files and, followed through #include "...", every file they
// read: the including file's folder first, then the build's -I folders.
ShaderReload::Times ShaderReload::sourceTimes() const {
    static const std::regex include(R"(^\s*#\s*include\s*"([^"]+)\")");
    Times times;
    std::vector<fs::path> todo;
    for (const std::string& f : stageFiles(shaders_))
        todo.push_back(root_ / "shaders" / f);
    while (!todo.empty()) {
        fs::path file = todo.back();
        todo.pop_back();
        std::error_code error;
        auto time = fs::last_write_time(file, error);
        if (!times.emplace(file, error ? fs::file_time_type::min() : time).second ||
            error)
            continue;
        std::ifstream in(file);
        std::smatch m;
        for (std::string line; std::getline(in, line);) {
            if (!std::regex_search(line, m, include)) continue;
            for (const fs::path& dir :
                 {file.parent_path(), root_ / "shaders" / "common", root_ / "shared"})
                if (fs::exists(dir / m[1].str())) {
                    todo.push_back(dir / m[1].str());
                    break;
                }
        }
    }
    return times;
}

std::optional<RtShaders> ShaderReload::poll() {
    if (Clock::now() - lastLook_ > std::chrono::milliseconds(500)) {
        lastLook_ = Clock::now();
        Times times = sourceTimes();
        if (times != seen_) pending_ = true;  // saved (or gone, or a new include)
        seen_ = std::move(times);
    }
    std::optional<RtShaders> fresh;
    {
        std::lock_guard lock(mutex_);
        if (busy_ && !done_) return std::nullopt;
        if (done_ && compiled_) {
            fresh = shaders_;
            fresh->spirvDir = work_.string();
            ++reloads_;
        }
        busy_ = done_ = false;
    }
    if (worker_.joinable()) worker_.join();
    // Not while the caller builds from work_: the next compile writes there.
    if (pending_ && !fresh) start();
    return fresh;
}

void ShaderReload::request() { pending_ = true; }

std::optional<RtShaders> ShaderReload::compileNow() {
    start();
    if (worker_.joinable()) worker_.join();
    return poll();
}

void ShaderReload::start() {
    pending_ = false;
    // the constructor said why
    if (!fs::exists(root_ / "shaders" / shaders_.raygen)) return;
    {
        std::lock_guard lock(mutex_);
        busy_ = true;
    }
    report("shaders: compiling", false);
    worker_ = std::thread([this] { compile(); });
}

// The build's command (cmake/Shaders.cmake) for every stage, into work_.
void ShaderReload::compile() {
    auto begin = Clock::now();
    fs::create_directories(work_);
    fs::path log = work_ / "glslang.log";
    for (const std::string& stage : stageFiles(shaders_)) {
        fs::path spv = work_ / (stage + ".spv");
        fs::create_directories(spv.parent_path());
        std::string validator =
            fs::exists(RG_GLSLANG_VALIDATOR) ? RG_GLSLANG_VALIDATOR : "glslangValidator";
        int status =
            runLogged({validator, "--quiet", "--target-env", "vulkan1.2", "--target-env",
                       "spirv1.4", "-I" + (root_ / "shaders" / "common").string(),
                       "-I" + (root_ / "shared").string(), "-o", spv.string(),
                       (root_ / "shaders" / stage).string()},
                      log, [this](int pid) {
                          std::lock_guard lock(mutex_);
                          child_ = pid;
                          if (stopping_) kill(pid, SIGTERM);
                      });
        {
            std::lock_guard lock(mutex_);
            child_ = 0;
            if (stopping_) return;
        }
        if (status != 0) {
            report(status < 0 ? "shaders: cannot run " + validator
                              : "shader error: " + firstError(log, root_, status),
                   true);
            std::lock_guard lock(mutex_);
            done_ = true, compiled_ = false;
            return;
        }
    }
    std::lock_guard lock(mutex_);
    seconds_ = std::chrono::duration<double>(Clock::now() - begin).count();
    done_ = true, compiled_ = true;
}

void ShaderReload::rebuilt(double pipelineSeconds) {
    char line[96];
    std::snprintf(line, sizeof line,
                  "shaders: reloaded (compiled in %.1f s, pipeline %.1f s)", seconds_,
                  pipelineSeconds);
    report(line, false);
}

void ShaderReload::rebuildFailed(const std::string& why) {
    report("shaders: the pipeline failed: " + why, true);
}

void ShaderReload::report(const std::string& status, bool failed) {
    {
        std::lock_guard lock(mutex_);
        status_ = status;
        failed_ = failed;
        lastStatus_ = Clock::now();
    }
    // the log says it too (and the tests wait for it)
    std::printf("%s\n", status.c_str());
    std::fflush(stdout);
}

std::string ShaderReload::status() const {
    std::lock_guard lock(mutex_);
    bool old = !failed_ && !busy_ && Clock::now() - lastStatus_ > std::chrono::seconds(5);
    return old ? std::string() : status_;  // an error stays until it is fixed
}

bool ShaderReload::failed() const {
    std::lock_guard lock(mutex_);
    return failed_;
}

}  // namespace rg
