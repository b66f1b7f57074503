// Faults a user meets (issue 29), each run for real on lavapipe: signals at
// random moments of a run, a full disk, special files and loops as inputs,
// requests larger than the device, broken JSON, control characters, a
// broken driver manifest and a display that goes away. Each asserts the exit
// code, exactly one line on stderr, and that no file is half-written.
#include "harness.h"

#include <stb_image_write.h>

#include <chrono>
#include <csignal>
#include <cstdlib>
#include <fcntl.h>
#include <filesystem>
#include <fstream>
#include <memory>
#include <random>
#include <sstream>
#include <sys/stat.h>
#include <sys/wait.h>
#include <thread>
#include <unistd.h>

namespace fs = std::filesystem;

namespace {

std::string readText(const std::string& path) {
    std::ifstream file(path, std::ios::binary);
    std::stringstream s;
    s << file.rdbuf();
    return s.str();
}

std::vector<std::string> lines(const std::string& text) {
    std::vector<std::string> out;
    std::stringstream s(text);
    for (std::string line; std::getline(s, line);) out.push_back(line);
    return out;
}

// A chapter started in the background, stdout and stderr to files.
struct Child {
    pid_t pid = -1;
    std::string out, err;

    Child(const std::string& exe, const std::vector<std::string>& args, const std::string& dir,
          const std::vector<std::string>& env = {}) {
        out = dir + "/stdout.txt";
        err = dir + "/stderr.txt";
        pid = fork();
        if (pid == 0) {
            int o = open(out.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
            int e = open(err.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
            dup2(o, 1);
            dup2(e, 2);
            for (const auto& kv : env) putenv(const_cast<char*>(kv.c_str()));
            std::vector<char*> argv{const_cast<char*>(exe.c_str())};
            for (const auto& a : args) argv.push_back(const_cast<char*>(a.c_str()));
            argv.push_back(nullptr);
            execv(exe.c_str(), argv.data());
            _exit(127);
        }
    }
    Child(const Child&) = delete;
    ~Child() {  // a test that stops early (a failed ASSERT) leaves no run behind
        if (pid > 0 && waitpid(pid, nullptr, WNOHANG) == 0) {
            kill(pid, SIGKILL);
            waitpid(pid, nullptr, 0);
        }
    }
    // The exit code (128 + signal if killed), or -1 after `seconds` (then killed).
    int wait(double seconds) {
        auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
        int status = 0;
        while (std::chrono::steady_clock::now() < end) {
            if (waitpid(pid, &status, WNOHANG) == pid) {
                pid = -1;
                return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
            }
            std::this_thread::sleep_for(std::chrono::milliseconds(20));
        }
        kill(pid, SIGKILL);
        waitpid(pid, &status, 0);
        pid = -1;
        return -1;
    }
    std::vector<std::string> errLines() const { return lines(readText(err)); }
    bool printed(const std::string& what) const { return readText(out).find(what) != std::string::npos; }
};

void expectNoPartialFiles(const std::string& dir) {
    for (const auto& e : fs::directory_iterator(dir))
        EXPECT_EQ(e.path().filename().string().find(".partial-"), std::string::npos) << e.path();
}

// A PFM that is whole: its header's size and exactly that many floats.
void expectCompletePfm(const std::string& path, int width, int height) {
    std::string text = readText(path);
    std::string header = "PF\n" + std::to_string(width) + " " + std::to_string(height) + "\n-1.0\n";
    ASSERT_EQ(text.compare(0, header.size(), header), 0) << path;
    EXPECT_EQ(text.size(), header.size() + size_t(width) * height * 12) << path;
}

std::mt19937& random() {
    static std::mt19937 generator = [] {
        unsigned seed = std::random_device{}();
        std::printf("random seed %u\n", seed);  // printed, so a failure can be replayed
        return std::mt19937(seed);
    }();
    return generator;
}

double uniform(double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(random()); }

void sleepSeconds(double s) { std::this_thread::sleep_for(std::chrono::duration<double>(s)); }

// Until the chapter has its device (its "Using [...]" line): the moment the
// rendering starts, from which the random delays count.
bool waitUntilStarted(Child& child, double seconds) {
    for (double t = 0; t < seconds; t += 0.02) {
        if (child.printed("Using [")) return true;
        sleepSeconds(0.02);
    }
    return false;
}

TEST(Interrupts, FirstSignalWritesTheFramesDone) {
    for (int signal : {SIGINT, SIGTERM, SIGHUP}) {
        std::string dir = rgtest::outputDir("faults_signal_" + std::to_string(signal));
        Child child(RG_EXE_11, {"--headless", "--validation", "--width", "96", "--height", "54", "--frames",
                                "1000000", "--output", dir + "/a.png"}, dir);
        ASSERT_TRUE(waitUntilStarted(child, 60));
        sleepSeconds(uniform(0.0, 2.5));  // a random moment: building, tracing or writing
        kill(child.pid, signal);
        ASSERT_EQ(child.wait(60), 130) << readText(child.err);
        auto err = child.errLines();
        ASSERT_EQ(err.size(), 1u) << readText(child.err);
        EXPECT_EQ(err[0].rfind("11_rough: interrupted by SIG", 0), 0u) << err[0];
        expectNoPartialFiles(dir);
        if (!fs::exists(dir + "/a.json")) {  // before the first frame: nothing at all
            EXPECT_NE(err[0].find("nothing written"), std::string::npos) << err[0];
            EXPECT_FALSE(fs::exists(dir + "/a.png"));
            continue;
        }
        nlohmann::json report = rgtest::readJson(dir + "/a.json");
        ASSERT_TRUE(report.contains("interrupted")) << report.dump();
        int done = report["interrupted"].value("frames_done", 0);
        EXPECT_GE(done, 1);
        EXPECT_LT(done, 1000000);
        EXPECT_EQ(report.value("frames", 0), done);
        EXPECT_EQ(report.value("validation_messages", 1), 0);
        rgtest::Png png = rgtest::readPng(dir + "/a.png");
        EXPECT_EQ(png.width, 96);
        EXPECT_EQ(png.height, 54);
        expectCompletePfm(dir + "/a.pfm", 96, 54);
    }
}

TEST(Interrupts, SecondSignalQuitsAtOnceLeavingNoPartialFile) {
    for (int round = 0; round < 3; ++round) {
        std::string dir = rgtest::outputDir("faults_second_signal_" + std::to_string(round));
        const std::string previous = "the previous file";
        std::ofstream(dir + "/a.png") << previous;
        // A large image, so that the second signal often lands in the write.
        Child child(RG_EXE_06, {"--headless", "--validation", "--width", "2048", "--height", "2048", "--frames",
                                "1000000", "--output", dir + "/a.png"}, dir);
        ASSERT_TRUE(waitUntilStarted(child, 60));
        sleepSeconds(uniform(0.5, 2.0));
        kill(child.pid, SIGINT);
        sleepSeconds(uniform(0.0, 0.4));
        kill(child.pid, SIGINT);
        ASSERT_EQ(child.wait(20), 130) << readText(child.err);
        auto err = child.errLines();
        ASSERT_EQ(err.size(), 1u) << readText(child.err);
        EXPECT_TRUE(err[0].find("interrupted again") != std::string::npos ||
                    err[0].find("interrupted by SIGINT") != std::string::npos) << err[0];
        expectNoPartialFiles(dir);
        // The old file as it was, or the new one whole: never a mix.
        if (readText(dir + "/a.png") != previous) {
            rgtest::Png png = rgtest::readPng(dir + "/a.png");
            EXPECT_EQ(png.width, 2048);
        }
        if (fs::exists(dir + "/a.pfm")) expectCompletePfm(dir + "/a.pfm", 2048, 2048);
    }
}

// A disk that fills up during the write: a small tmpfs in a mount namespace
// of its own (unshare; skipped where that is not allowed).
TEST(FullDisk, AFailedWriteKeepsThePreviousFile) {
    if (std::system("unshare -m true 2>/dev/null") != 0) GTEST_SKIP() << "no mount namespace (unshare -m) here";
    std::string dir = rgtest::outputDir("faults_full_disk");
    std::string script = dir + "/run.sh";
    std::ofstream(script) << "set -u\n"
                             "d=" << dir << "/disk\nmkdir -p $d\n"
                             "mount -t tmpfs -o size=512k tmpfs $d || exit 99\n"
                             "printf 'the previous file' > $d/a.png\n"
                             "head -c 500k /dev/zero > $d/fill 2>/dev/null\n"
                             "'" RG_EXE_06 "' --headless --validation --width 320 --height 180 --frames 2 --output $d/a.png "
                             ">/dev/null 2>" << dir << "/stderr.txt\n"
                             "echo rc=$?\nls -a $d\ncat $d/a.png; echo\n";
    rgtest::RunResult r = rgtest::run("/usr/bin/unshare", {"-m", "/bin/sh", script});
    if (r.output.find("rc=") == std::string::npos) GTEST_SKIP() << "cannot mount a tmpfs here: " << r.output;
    EXPECT_NE(r.output.find("rc=1"), std::string::npos) << r.output;
    EXPECT_EQ(r.output.find(".partial-"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("the previous file"), std::string::npos) << r.output;
    auto err = lines(readText(dir + "/stderr.txt"));
    ASSERT_EQ(err.size(), 1u) << readText(dir + "/stderr.txt");
    EXPECT_NE(err[0].find("No space left on device"), std::string::npos) << err[0];
}

// Runs a chapter that must refuse at once: exit 2 and one line with `needle`.
void expectRefused(const std::vector<std::string>& args, const std::string& needle, const std::string& name,
                   const char* exe = RG_EXE_06, int code = 2, const std::vector<std::string>& env = {}) {
    std::string dir = rgtest::outputDir(name);
    std::vector<std::string> all = {"--headless", "--validation", "--output", dir + "/out/a.png"};
    all.insert(all.end(), args.begin(), args.end());
    Child child(exe, all, dir, env);
    EXPECT_EQ(child.wait(30), code) << name << ": " << readText(child.err);
    auto err = child.errLines();
    ASSERT_EQ(err.size(), 1u) << name << ": " << readText(child.err);
    EXPECT_NE(err[0].find(needle), std::string::npos) << name << ": " << err[0];
    EXPECT_FALSE(fs::exists(dir + "/out/a.png")) << name;
}

std::string sceneWithSky(const std::string& dir, const std::string& image) {
    nlohmann::json scene = rgtest::readJson(RG_SOURCE_DIR "/assets/scenes/default.json");
    scene["sky"] = {{"image", image}};
    std::string path = dir + "/sky_" + std::to_string(std::hash<std::string>{}(image)) + ".json";
    std::ofstream(path) << scene.dump();
    return path;
}

TEST(SpecialFiles, RefusedWithOneLineNamingTheKey) {
    std::string dir = rgtest::outputDir("faults_special");
    std::string fifo = dir + "/fifo", loop = dir + "/loop";
    ASSERT_EQ(mkfifo(fifo.c_str(), 0644), 0);
    fs::create_symlink(dir + "/loop2", loop);
    fs::create_symlink(loop, dir + "/loop2");
    expectRefused({"--scene", fifo}, "--scene: " + fifo + ": is not a regular file", "faults_fifo_scene");
    expectRefused({"--scene", loop}, "--scene: " + loop + ": a loop of symbolic links", "faults_loop_scene");
    expectRefused({"--scene", "/dev/zero"}, "is not a regular file", "faults_device_scene");
    expectRefused({"--scene", sceneWithSky(dir, fifo)}, "sky.image: " + fifo + ": is not a regular file",
                  "faults_fifo_sky");
    expectRefused({"--scene", sceneWithSky(dir, "/dev/zero")}, "sky.image: /dev/zero: is not a regular file",
                  "faults_device_sky");
    expectRefused({"--scene", sceneWithSky(dir, loop)}, "sky.image: " + loop + ": a loop of symbolic links",
                  "faults_loop_sky");
    std::string truncated = dir + "/truncated.png";
    std::ofstream(truncated) << "\x89PNG\r\n\x1a\n";
    expectRefused({"--scene", sceneWithSky(dir, truncated)}, "sky.image: cannot read", "faults_truncated_sky");
}

TEST(Oversized, RefusedBeforeAnyWorkNamingTheLimit) {
    // Over any device's limits (maxImageDimension2D is at most 16384 on
    // lavapipe, and 16384^2 rays pass every maxRayDispatchInvocationCount seen).
    for (const char* exe : {RG_EXE_01, RG_EXE_06, RG_EXE_10})
        expectRefused({"--width", "16384", "--height", "16384"}, "is too large for this device", "faults_oversized",
                      exe);
}

TEST(Oversized, ASkyImageLargerThanAStorageBufferIsRefused) {
    std::string dir = rgtest::outputDir("faults_big_sky");
    int w = 4096, h = 2049;  // 128 MiB and a row as RGBA floats: over lavapipe's maxStorageBufferRange
    std::vector<unsigned char> pixels(size_t(w) * h * 3, 128);
    ASSERT_TRUE(stbi_write_png((dir + "/big.png").c_str(), w, h, 3, pixels.data(), w * 3));
    Child child(RG_EXE_06, {"--headless", "--validation", "--width", "32", "--height", "18", "--frames", "1",
                            "--scene", sceneWithSky(dir, dir + "/big.png"), "--output", dir + "/a.png"}, dir);
    int code = child.wait(120);
    if (code == 0) GTEST_SKIP() << "this device's storage buffers hold the sky";  // not lavapipe
    EXPECT_EQ(code, 2);
    auto err = child.errLines();
    ASSERT_EQ(err.size(), 1u) << readText(child.err);
    EXPECT_NE(err[0].find("sky.image: its 4096x2049 texels need"), std::string::npos) << err[0];
    EXPECT_NE(err[0].find("maxStorageBufferRange"), std::string::npos) << err[0];
}

TEST(Inputs, JsonErrorsNameLineColumnAndReason) {
    std::string dir = rgtest::outputDir("faults_json");
    std::ofstream(dir + "/number.json") << "{\n  \"camera\": {\"fov_y_deg\": 1e400}\n}\n";
    expectRefused({"--scene", dir + "/number.json"}, "number.json:2:", "faults_json_number");
    expectRefused({"--scene", dir + "/number.json"}, "number overflow parsing '1e400'", "faults_json_number");
    std::ofstream(dir + "/cut.json") << "{\n  \"camera\": {\n";
    expectRefused({"--scene", dir + "/cut.json"}, "cut.json:3:", "faults_json_cut");
    expectRefused({"--scene", dir + "/cut.json"}, "unexpected end of input", "faults_json_cut");
}

TEST(Inputs, ControlCharactersAreEscaped) {
    expectRefused({"--scene", "bad\nname\x1b[31m"}, "bad\\x0aname\\x1b[31m: no such file", "faults_control");
}

TEST(Driver, ABrokenManifestIsExplainedLikeAMissingDriver) {
    std::string dir = rgtest::outputDir("faults_manifest");
    std::ofstream(dir + "/icd.json") << "{\n    \"ICD\": {\n        \"api_version\": \"1.4.305\",\n        \"li";
    // The loader answers VK_ERROR_OUT_OF_HOST_MEMORY or VK_ERROR_INCOMPATIBLE_DRIVER,
    // depending on where the file is cut; both get the advice.
    expectRefused({}, "Vulkan driver", "faults_manifest", RG_EXE_06, 1, {"VK_DRIVER_FILES=" + dir + "/icd.json"});
    expectRefused({}, "readable driver .json", "faults_manifest", RG_EXE_06, 1,
                  {"VK_DRIVER_FILES=" + dir + "/icd.json"});
    std::ofstream(dir + "/icd60.json") << readText("/usr/share/vulkan/icd.d/lvp_icd.json").substr(0, 60);
    expectRefused({}, "Vulkan driver", "faults_manifest", RG_EXE_06, 1, {"VK_DRIVER_FILES=" + dir + "/icd60.json"});
}

TEST(Window, ALostDisplayEndsTheRunWithOneLine) {
    std::string dir = rgtest::outputDir("faults_lost_display");
    // A display of this test's own (a number from the process id), so that
    // no other X server or earlier run is in the way.
    std::string number = std::to_string(300 + getpid() % 600), display = ":" + number;
    pid_t server = fork();
    if (server == 0) {
        int null = open("/dev/null", O_WRONLY);
        dup2(null, 1);
        dup2(null, 2);
        unsetenv("LD_PRELOAD");  // the sanitizer pass preloads its runtime for the chapters, not for X
        execlp("Xvfb", "Xvfb", display.c_str(), "-nolisten", "tcp", "-screen", "0", "640x480x24", (char*)nullptr);
        _exit(127);
    }
    struct Reaper {  // the server goes when the test ends, however it ends
        pid_t pid;
        ~Reaper() {
            if (waitpid(pid, nullptr, WNOHANG) == 0) kill(pid, SIGKILL), waitpid(pid, nullptr, 0);
        }
    } reaper{server};
    for (int i = 0; i < 500 && !fs::exists("/tmp/.X11-unix/X" + number); ++i) sleepSeconds(0.02);
    if (!fs::exists("/tmp/.X11-unix/X" + number)) GTEST_SKIP() << "no Xvfb here";
    // Xvfb names its display a moment before it serves windows (it still
    // compiles its keymap): a chapter started too early cannot open one; retry.
    std::unique_ptr<Child> child;
    for (int attempt = 0; attempt < 20; ++attempt) {
        child = std::make_unique<Child>(RG_EXE_02, std::vector<std::string>{"--validation", "--output", dir + "/a.png"},
                                        dir, std::vector<std::string>{"DISPLAY=" + display, "XDG_RUNTIME_DIR=/tmp"});
        bool exited = false;
        for (double t = 0; t < 60 && !child->printed("Using [") && !exited; t += 0.02) {
            if (waitpid(child->pid, nullptr, WNOHANG) == child->pid) exited = true, child->pid = -1;
            sleepSeconds(0.02);
        }
        if (!exited) break;  // it has its device, so its window too
        sleepSeconds(0.5);
    }
    ASSERT_TRUE(child->printed("Using [")) << display << ": " << readText(child->err);
    sleepSeconds(uniform(0.5, 2.0));
    kill(server, SIGTERM);
    waitpid(server, nullptr, 0);
    EXPECT_EQ(child->wait(30), 1);
    auto err = child->errLines();
    ASSERT_EQ(err.size(), 1u) << readText(child->err);
    EXPECT_NE(err[0].find("the display connection was lost"), std::string::npos) << err[0];
}

}  // namespace
