// Test helpers: run a chapter executable as a user would, then read the PNG
// and the JSON report it wrote.
#pragma once
#include <gtest/gtest.h>
#include <glm/glm.hpp>
#include <nlohmann/json.hpp>

#include <cstdint>
#include <string>
#include <vector>

namespace rgtest {

struct RunResult {
    int exitCode = -1;
    std::string output;  // stdout and stderr together
};

// Runs `exe args...` (validation messages are printed to stderr).
RunResult run(const std::string& exe, const std::vector<std::string>& args);

struct Png {
    int width = 0, height = 0;
    std::vector<uint8_t> rgb;
    const uint8_t* at(int x, int y) const { return &rgb[3 * (size_t(y) * width + x)]; }
};
Png readPng(const std::string& path);  // fails the test when unreadable
nlohmann::json readJson(const std::string& path);

// A fresh folder for one test's files, under the build tree.
std::string outputDir(const std::string& name);

// The display value (0-255) that a linear value turns into (shared/core/display.h).
int display8(double linear);

// Every report from a clean run: right size, validation clean, GPU time measured.
void expectCleanReport(const nlohmann::json& report, const std::string& chapter, int width, int height);

// True when a display exists. Under xvfb-run (RG_REQUIRE_DISPLAY=1) a missing
// display is also a test failure; elsewhere the caller skips.
bool haveDisplay();

// A windowed run under xvfb-run: exit 0, a report that says windowed, no
// validation message. Skips without a display, fails under RG_REQUIRE_DISPLAY.
void expectCleanWindowedRun(const std::string& exe, const std::string& name, int frames);

// Runs a ray tracing chapter headless with --reference on `scene` (empty:
// its default) and checks the error bounds every shading chapter must meet:
// at most 0.1 % of pixels off by more than 1/255, RMSE <= 1e-3, no NaN/Inf.
// Returns the report for further checks.
nlohmann::json expectMatchesReference(const std::string& exe, const std::string& scene, const std::string& name,
                                      const std::vector<std::string>& extraArgs = {});

// A scene file's pinhole camera (position, look_at, fov_y_deg, up: +y unless
// given), as the chapters aim it: where a point lands in a width x height
// picture, in pixel coordinates, top row first.
struct SceneCamera {
    SceneCamera(const nlohmann::json& scene, int width, int height);
    glm::dvec2 project(const glm::dvec3& p) const;
    // how many pixels a length across the view at p spans (a sphere's radius)
    double pixelsAcross(const glm::dvec3& p, double length) const;
    glm::dvec3 eye, forward, right, up;
    double tanHalf;
    int width, height;
};
glm::dvec3 vec3(const nlohmann::json& xyz);  // [x, y, z]

// The hard-case scenes under tests/scenes/.
std::vector<std::string> hardCaseScenes();
// Chapter 12's mesh scenes under tests/mesh_scenes/ (the chapters before refuse them).
std::vector<std::string> meshScenes();

}  // namespace rgtest
