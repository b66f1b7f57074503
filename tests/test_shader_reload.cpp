// Shader hot reload without a window (shared/viewer/shader_reload.h): in a copy of
// the shader tree, a saved file that a stage includes compiles every stage
// again into SPIR-V; an error names its file and line and gives nothing to
// build; F5 compiles unchanged sources; no sources means no reload. The
// window's side (the pipeline swapped, the error in the overlay) is
// tests/test_interactive.py --reload.
#include "viewer/shader_reload.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <fstream>
#include <sstream>
#include <thread>

namespace fs = std::filesystem;

namespace {

// Chapter 04's stages.
rg::RtShaders chapter04() {
    return {.raygen = "04_raygen_miss/raygen.rgen",
            .miss = {"common/sky.rmiss"},
            .hitGroups = {{.closestHit = "common/quad.rchit"},
                          {.closestHit = "common/sphere.rchit", .intersection = "common/sphere.rint"}}};
}

struct ShaderReloadTest : ::testing::Test {
    fs::path tree;
    void SetUp() override {
        tree = fs::temp_directory_path() /
               ("rg-reload-" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
        fs::remove_all(tree);
        fs::create_directories(tree / "shared");
        fs::copy(rg::builtSourceRoot() / "shaders", tree / "shaders", fs::copy_options::recursive);
        fs::copy(rg::builtSourceRoot() / "shared" / "host_device.h", tree / "shared");
    }
    void TearDown() override { fs::remove_all(tree); }

    std::string read(const fs::path& p) {
        std::ifstream in(tree / p);
        std::stringstream s;
        s << in.rdbuf();
        return s.str();
    }
    void write(const fs::path& p, const std::string& text) { std::ofstream(tree / p) << text; }

    // Polls as a frame loop would until a compile gives stages, an error
    // shows (unless it is an old one: `errorEnds` false), or 60 s pass.
    std::optional<rg::RtShaders> waitFor(rg::ShaderReload& reload, bool errorEnds = true) {
        auto end = std::chrono::steady_clock::now() + std::chrono::seconds(60);
        while (std::chrono::steady_clock::now() < end) {
            if (auto compiled = reload.poll()) return compiled;
            if (errorEnds && reload.failed()) return std::nullopt;
            std::this_thread::sleep_for(std::chrono::milliseconds(20));
        }
        ADD_FAILURE() << "no compile ended within 60 s: " << reload.status();
        return std::nullopt;
    }
};

bool isSpirv(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    uint32_t magic = 0;
    in.read(reinterpret_cast<char*>(&magic), 4);
    return in && magic == 0x07230203u;
}

}  // namespace

TEST_F(ShaderReloadTest, NothingChangedNothingCompiles) {
    rg::ShaderReload reload(chapter04(), tree);
    auto end = std::chrono::steady_clock::now() + std::chrono::milliseconds(1500);  // three looks
    while (std::chrono::steady_clock::now() < end) {
        EXPECT_FALSE(reload.poll().has_value());
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    EXPECT_EQ(reload.status(), "");
}

TEST_F(ShaderReloadTest, ASavedIncludeCompilesEveryStage) {
    rg::ShaderReload reload(chapter04(), tree);
    // sky.glsl is no stage: sky.rmiss includes it.
    write("shaders/common/sky.glsl", read("shaders/common/sky.glsl") + "\n// edited\n");
    std::optional<rg::RtShaders> compiled = waitFor(reload);
    ASSERT_TRUE(compiled.has_value()) << reload.status();
    EXPECT_FALSE(compiled->spirvDir.empty());
    EXPECT_EQ(compiled->raygen, chapter04().raygen);
    for (const char* stage : {"04_raygen_miss/raygen.rgen", "common/sky.rmiss", "common/quad.rchit",
                              "common/sphere.rchit", "common/sphere.rint"})
        EXPECT_TRUE(isSpirv(fs::path(compiled->spirvDir) / (std::string(stage) + ".spv"))) << stage;
    EXPECT_EQ(reload.reloads(), 1);
    EXPECT_FALSE(reload.poll().has_value());  // once
}

TEST_F(ShaderReloadTest, AnErrorNamesItsFileAndLineAndGivesNoStages) {
    rg::ShaderReload reload(chapter04(), tree);
    std::string sky = read("shaders/common/sky.glsl");
    std::string good = "x = (x % w + w) % w;";
    size_t at = sky.find(good);
    ASSERT_NE(at, std::string::npos);
    int line = 1 + int(std::count(sky.begin(), sky.begin() + at, '\n'));
    write("shaders/common/sky.glsl", sky.substr(0, at) + "x = (x % w + q) % w;" + sky.substr(at + good.size()));
    EXPECT_FALSE(waitFor(reload).has_value());
    EXPECT_TRUE(reload.failed());
    std::string expected = "shader error: shaders/common/sky.glsl:" + std::to_string(line) + ": 'q'";
    EXPECT_EQ(reload.status().rfind(expected, 0), 0u) << reload.status();
    EXPECT_EQ(reload.status().find(tree.string()), std::string::npos) << "the path is the tree's own";

    write("shaders/common/sky.glsl", sky);  // fixed
    EXPECT_TRUE(waitFor(reload, false).has_value()) << reload.status();
    EXPECT_FALSE(reload.failed());
}

TEST_F(ShaderReloadTest, F5CompilesUnchangedSources) {
    rg::ShaderReload reload(chapter04(), tree);
    reload.request();
    EXPECT_TRUE(waitFor(reload).has_value()) << reload.status();
}

TEST_F(ShaderReloadTest, NoSourcesNoReload) {
    fs::remove_all(tree / "shaders");
    rg::ShaderReload reload(chapter04(), tree);
    EXPECT_NE(reload.status().find("reload is off"), std::string::npos) << reload.status();
    reload.request();
    for (int i = 0; i < 10; ++i) EXPECT_FALSE(reload.poll().has_value());
}
