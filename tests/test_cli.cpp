// Bad input on the command line: one clear message and exit code 2, for
// every chapter (the options are shared, the test runs each executable).
#include "harness.h"

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace {

struct BadInput {
    std::vector<std::string> args;
    std::string mentions;  // what the one-line message must name
};

class CommandLine : public ::testing::TestWithParam<std::string> {};

TEST_P(CommandLine, BadInputExitsWithCode2AndOneMessage) {
    const std::vector<BadInput> cases = {
        {{"--width", "0"}, "--width"},
        {{"--height", "-5"}, "--height"},
        {{"--width", "abc"}, "--width"},
        {{"--frames", "0"}, "--frames"},
        {{"--no-such-flag"}, "no-such-flag"},
        {{"--width"}, "--width"},
        {{"--device", "-1"}, "--device"},
    };
    for (const auto& c : cases) {
        std::vector<std::string> args = c.args;
        args.push_back("--headless");
        rgtest::RunResult r = rgtest::run(GetParam(), args);
        EXPECT_EQ(r.exitCode, 2) << c.args[0] << ": " << r.output;
        EXPECT_NE(r.output.find(c.mentions), std::string::npos) << r.output;
        EXPECT_NE(r.output.find("error"), std::string::npos) << r.output;
    }
}

TEST_P(CommandLine, HelpExitsWithCode0) {
    rgtest::RunResult r = rgtest::run(GetParam(), {"--help"});
    EXPECT_EQ(r.exitCode, 0);
    EXPECT_NE(r.output.find("--headless"), std::string::npos);
}

TEST_P(CommandLine, MissingDeviceIndexIsAClearError) {
    rgtest::RunResult r = rgtest::run(GetParam(), {"--headless", "--device", "7", "--output",
                                                   rgtest::outputDir("cli_device") + "/x.png"});
    EXPECT_EQ(r.exitCode, 1) << r.output;
    EXPECT_NE(r.output.find("--device 7"), std::string::npos) << r.output;
}

// A run never writes over its scene file: the report of --output floor.png
// would be floor.json. One line, exit 2, and the scene is left as it was.
TEST_P(CommandLine, OutputThatWouldOverwriteTheSceneIsRefused) {
    std::string dir = rgtest::outputDir("cli_clash_" + std::to_string(std::hash<std::string>{}(GetParam()) % 100000));
    rgtest::RunResult same = rgtest::run(GetParam(), {"--headless", "--output", dir + "/a.png", "--report", dir + "/a.png"});
    EXPECT_EQ(same.exitCode, 2) << same.output;
    EXPECT_NE(same.output.find("--output and --report name the same file"), std::string::npos) << same.output;
    if (GetParam().find("01_") != std::string::npos || GetParam().find("02_") != std::string::npos)
        return;  // no --scene before chapter 03
    std::string scene = dir + "/floor.json", text = "{\"objects\": []}\n";  // refused before it is read
    std::ofstream(scene) << text;
    auto contents = [&] { std::stringstream s; s << std::ifstream(scene).rdbuf(); return s.str(); };
    for (const std::vector<std::string>& args : std::vector<std::vector<std::string>>{
             {"--output", dir + "/floor.png"}, {"--output", dir + "/x.png", "--report", dir + "/./floor.json"}}) {
        std::vector<std::string> all = {"--headless", "--width", "16", "--height", "16", "--frames", "1", "--scene", scene};
        all.insert(all.end(), args.begin(), args.end());
        rgtest::RunResult r = rgtest::run(GetParam(), all);
        EXPECT_EQ(r.exitCode, 2) << r.output;
        EXPECT_NE(r.output.find("would overwrite the scene file"), std::string::npos) << r.output;
        EXPECT_EQ(contents(), text);
    }
}

// A run whose output cannot be written fails with one line naming the file
// (a full disk: /dev/full takes the open, refuses the bytes).
TEST_P(CommandLine, UnwritableOutputIsAnErrorNamingTheFile) {
    std::string dir = rgtest::outputDir("cli_full_" + std::to_string(std::hash<std::string>{}(GetParam()) % 100000));
    rgtest::RunResult r = rgtest::run(GetParam(), {"--headless", "--width", "16", "--height", "16", "--frames", "1",
                                                   "--output", dir + "/x.png", "--report", "/dev/full"});
    EXPECT_EQ(r.exitCode, 1) << r.output;
    EXPECT_NE(r.output.find("cannot write /dev/full: No space left on device"), std::string::npos) << r.output;
    size_t errors = 0;
    for (size_t at = r.output.find("error:"); at != std::string::npos; at = r.output.find("error:", at + 1)) ++errors;
    EXPECT_EQ(errors, 1u) << r.output;
}

// Without --output a chapter writes into out/ below the folder it runs in,
// making it; a folder named by --output is made too.
TEST_P(CommandLine, OutputsGoToOutByDefault) {
    std::string exe = GetParam(), name = std::filesystem::path(exe).filename().string();
    std::string dir = rgtest::outputDir("cli_out_" + name);
    rgtest::RunResult r = rgtest::run("sh", {"-c", "cd \"$0\" && exec \"$1\" --headless --width 16 --height 16 --frames 1",
                                             dir, exe});
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_TRUE(std::filesystem::is_regular_file(dir + "/out/" + name + ".png")) << r.output;
    EXPECT_TRUE(std::filesystem::is_regular_file(dir + "/out/" + name + ".json")) << r.output;
    r = rgtest::run(exe, {"--headless", "--width", "16", "--height", "16", "--frames", "1", "--output",
                          dir + "/a/b/x.png"});
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_TRUE(std::filesystem::is_regular_file(dir + "/a/b/x.png")) << r.output;
}

TEST_P(CommandLine, AnOutputFolderThatCannotBeMadeIsOneError) {
    rgtest::RunResult r = rgtest::run(GetParam(), {"--headless", "--output", "/proc/rayglass/x.png"});
    EXPECT_EQ(r.exitCode, 2) << r.output;
    EXPECT_NE(r.output.find("error: cannot make the folder /proc/rayglass for /proc/rayglass/x.png"), std::string::npos)
        << r.output;
}

// No Vulkan driver at all: say what to install, not where in the code it failed.
TEST_P(CommandLine, NoDriverSaysWhatToInstall) {
    rgtest::RunResult r = rgtest::run("env", {"VK_ICD_FILENAMES=/nonexistent.json", "VK_DRIVER_FILES=/nonexistent.json",
                                              GetParam(), "--headless", "--frames", "1", "--output",
                                              rgtest::outputDir("cli_nodriver_" + std::to_string(std::hash<std::string>{}(GetParam()) % 100000)) + "/x.png"});
    EXPECT_EQ(r.exitCode, 1) << r.output;
    EXPECT_NE(r.output.find("no Vulkan driver found"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("tools/setup.sh"), std::string::npos) << r.output;
    EXPECT_EQ(r.output.find("context.cpp"), std::string::npos) << r.output;
}

}  // namespace

INSTANTIATE_TEST_SUITE_P(Chapters, CommandLine, ::testing::ValuesIn(std::vector<std::string>{RG_CHAPTER_EXES}));
