#include "harness.h"

#include "core/display.h"

#include <stb_image.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sys/wait.h>

namespace rgtest {

namespace {
std::string quote(const std::string& s) {
    std::string q(1, '\'');
    for (char c : s) {
        if (c == '\'') q.append("'\\''");
        else q.push_back(c);
    }
    q.push_back('\'');
    return q;
}
}  // namespace

RunResult run(const std::string& exe, const std::vector<std::string>& args) {
    std::string command = quote(exe);
    for (const auto& a : args) {
        command.push_back(' ');
        command.append(quote(a));
    }
    command.append(" 2>&1");
    RunResult result;
    FILE* pipe = popen(command.c_str(), "r");
    if (!pipe) return result;
    std::array<char, 4096> buffer;
    size_t n;
    while ((n = fread(buffer.data(), 1, buffer.size(), pipe)) > 0) result.output.append(buffer.data(), n);
    int status = pclose(pipe);
    result.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
    return result;
}

Png readPng(const std::string& path) {
    Png png;
    int channels = 0;
    unsigned char* data = stbi_load(path.c_str(), &png.width, &png.height, &channels, 3);
    EXPECT_NE(data, nullptr) << "cannot read " << path;
    if (data) {
        png.rgb.assign(data, data + size_t(png.width) * png.height * 3);
        stbi_image_free(data);
    }
    return png;
}

nlohmann::json readJson(const std::string& path) {
    std::ifstream file(path);
    EXPECT_TRUE(file.good()) << "cannot read " << path;
    if (!file) return {};
    return nlohmann::json::parse(file, nullptr, false);
}

glm::dvec3 vec3(const nlohmann::json& xyz) { return {double(xyz[0]), double(xyz[1]), double(xyz[2])}; }

SceneCamera::SceneCamera(const nlohmann::json& scene, int width, int height)
    : eye(vec3(scene["camera"]["position"])), width(width), height(height) {
    const nlohmann::json& camera = scene["camera"];
    forward = glm::normalize(vec3(camera["look_at"]) - eye);
    glm::dvec3 sky = camera.contains("up") ? vec3(camera["up"]) : glm::dvec3(0, 1, 0);
    right = glm::normalize(glm::cross(forward, sky));
    up = glm::cross(right, forward);
    tanHalf = std::tan(double(camera["fov_y_deg"]) * 3.14159265358979323846 / 360);
}

glm::dvec2 SceneCamera::project(const glm::dvec3& p) const {
    glm::dvec3 d = p - eye;
    double z = glm::dot(d, forward);
    return {(glm::dot(d, right) / z / (tanHalf * width / height) + 1) / 2 * width,
            (1 - glm::dot(d, up) / z / tanHalf) / 2 * height};
}

double SceneCamera::pixelsAcross(const glm::dvec3& p, double length) const {
    return std::abs(project(p + length * right).x - project(p).x);
}

std::string outputDir(const std::string& name) {
    std::filesystem::path dir = std::filesystem::path(RG_TEST_OUTPUT_DIR) / name;
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
    return dir.string();
}

int display8(double linear) { return rg::toDisplay8(linear); }

void expectCleanReport(const nlohmann::json& report, const std::string& chapter, int width, int height) {
    ASSERT_TRUE(report.is_object());
    EXPECT_EQ(report.value("chapter", ""), chapter);
    EXPECT_EQ(report.value("width", 0), width);
    EXPECT_EQ(report.value("height", 0), height);
    EXPECT_EQ(report.value("validation_messages", -1), 0);
    EXPECT_TRUE(report.value("validation", false));
    EXPECT_FALSE(report.value("device", "").empty());
    EXPECT_FALSE(report.value("driver", "").empty());
    ASSERT_TRUE(report.contains("gpu_ms"));
    EXPECT_GT(report["gpu_ms"].value("median", 0.0), 0.0);
    EXPECT_LE(report["gpu_ms"].value("min", 0.0), report["gpu_ms"].value("median", 0.0));
    EXPECT_LE(report["gpu_ms"].value("median", 0.0), report["gpu_ms"].value("max", 0.0));
    EXPECT_GE(report.value("frames", 0), 1);
}

nlohmann::json expectMatchesReference(const std::string& exe, const std::string& scene, const std::string& name,
                                      const std::vector<std::string>& extraArgs) {
    std::string dir = outputDir(name);
    std::vector<std::string> args = {"--headless", "--validation", "--reference", "--width", "160", "--height", "90",
                                     "--output", dir + "/out.png"};
    if (std::find(extraArgs.begin(), extraArgs.end(), "--frames") == extraArgs.end())
        args.insert(args.end(), {"--frames", "2"});
    if (!scene.empty()) args.insert(args.end(), {"--scene", scene});
    args.insert(args.end(), extraArgs.begin(), extraArgs.end());
    RunResult r = run(exe, args);
    EXPECT_EQ(r.exitCode, 0) << r.output;
    nlohmann::json report = readJson(dir + "/out.json");
    if (!report.is_object() || !report.contains("error")) {
        ADD_FAILURE() << name << ": no error in the report";
        return report;
    }
    expectCleanReport(report, report.value("chapter", ""), 160, 90);
    const auto& e = report["error"];
    EXPECT_LE(e.value("frac_over_1_255", 1.0), 0.001) << name;
    EXPECT_LE(e.value("rmse", 1.0), 1e-3) << name;
    EXPECT_EQ(e.value("non_finite_pixels", 1), 0) << name;
    EXPECT_EQ(report.value("non_finite_values", 1), 0) << name;
    EXPECT_GE(report.value("rays_per_frame", 0), 160 * 90) << name;
    return report;
}

static std::vector<std::string> scenesIn(const std::string& folder) {
    std::vector<std::string> scenes;
    for (const auto& entry : std::filesystem::directory_iterator(folder))
        if (entry.path().extension() == ".json") scenes.push_back(entry.path().string());
    std::sort(scenes.begin(), scenes.end());
    return scenes;
}

std::vector<std::string> hardCaseScenes() { return scenesIn(RG_SOURCE_DIR "/tests/scenes"); }
std::vector<std::string> meshScenes() { return scenesIn(RG_SOURCE_DIR "/tests/mesh_scenes"); }

bool haveDisplay() {
    if (std::getenv("DISPLAY")) return true;
    EXPECT_EQ(std::getenv("RG_REQUIRE_DISPLAY"), nullptr) << "xvfb-run gave no DISPLAY";
    return false;
}

void expectCleanWindowedRun(const std::string& exe, const std::string& name, int frames) {
    if (!haveDisplay()) GTEST_SKIP() << "no DISPLAY: run through xvfb-run";
    std::string dir = outputDir(name);
    RunResult r = run(exe, {"--validation", "--width", "160", "--height", "90", "--frames", std::to_string(frames),
                            "--output", dir + "/" + name + ".png"});
    ASSERT_EQ(r.exitCode, 0) << r.output;
    nlohmann::json report = readJson(dir + "/" + name + ".json");
    EXPECT_FALSE(report.value("headless", true));
    EXPECT_EQ(report.value("frames", 0), frames);
    EXPECT_EQ(report.value("validation_messages", -1), 0);
}

}  // namespace rgtest
