// Shader hot reload (docs/index.md, "Playing with a chapter"): in a window,
// saving one of the chapter's GLSL sources, or anything they include, or
// pressing F5 compiles its stages again, in the background, with the same
// glslangValidator and flags as the build, from the source tree the chapter
// was built from (--shader-source names another). The viewer then rebuilds
// the pipeline from the new SPIR-V and keeps the camera. A compile error is
// one line with file and line; the last good pipeline keeps running.
#pragma once
#include "raytracing/rt_pipeline.h"

#include <chrono>
#include <filesystem>
#include <map>
#include <mutex>
#include <optional>
#include <string>
#include <thread>

namespace rg {

// The tree this binary was built from (where shaders/ and shared/ are).
std::filesystem::path builtSourceRoot();

class ShaderReload {
public:
    // shaders: the pipeline's stages, as paths under <sourceRoot>/shaders.
    ShaderReload(RtShaders shaders, std::filesystem::path sourceRoot);
    ~ShaderReload();
    ShaderReload(const ShaderReload&) = delete;
    ShaderReload& operator=(const ShaderReload&) = delete;

    void request();  // F5: compile now, changed or not

    // Compiles every stage now and waits: the stages (spirvDir set, valid
    // while this object lives), or nothing, and status() says why (the
    // first error's file and line). --shader-source's first pipeline.
    std::optional<RtShaders> compileNow();

    // Once a frame. Looks at the sources' times (every half second) and
    // starts a compile when one changed; returns the compiled stages
    // (RtShaders::spirvDir set) once, when every stage compiled.
    std::optional<RtShaders> poll();

    // What the caller did with poll()'s stages: built the pipeline (in
    // `seconds`), or could not.
    void rebuilt(double seconds);
    void rebuildFailed(const std::string& why);

    // For the overlay: what happened last ("" before anything), and
    // whether that was an error (then it names the file and line).
    std::string status() const;
    bool failed() const;
    int reloads() const { return reloads_; }

private:
    using Times = std::map<std::filesystem::path, std::filesystem::file_time_type>;
    Times sourceTimes() const;  // every stage's file and what it includes
    void start();
    void compile();  // on worker_: every stage, in order, stops at the first error
    void report(const std::string& status, bool failed);

    RtShaders shaders_;
    std::filesystem::path root_, work_;
    Times seen_;
    std::thread worker_;
    mutable std::mutex mutex_;  // guards what the worker writes below
    bool busy_ = false, done_ = false, compiled_ = false, failed_ = false,
         pending_ = false;
    int child_ = 0;  // the running validator's process id
    bool stopping_ = false;
    std::string status_;
    double seconds_ = 0;  // of the last compile
    int reloads_ = 0;
    std::chrono::steady_clock::time_point lastLook_, lastStatus_;
};

}  // namespace rg
