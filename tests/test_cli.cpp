// Bad input on the command line: one clear message and exit code 2, for
// every chapter (the options are shared, the test runs each executable).
#include "harness.h"

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

}  // namespace

INSTANTIATE_TEST_SUITE_P(Chapters, CommandLine, ::testing::ValuesIn(std::vector<std::string>{RG_CHAPTER_EXES}));
