// The window's camera (shared/viewer/camera_control.h) and the parameter
// declaration that feeds both the command line and the overlay
// (shared/core/params.h): pure CPU, no window.
#include <gtest/gtest.h>

#include "core/params.h"
#include "raytracing/rt_scene.h"
#include "viewer/camera_control.h"

#include <CLI/CLI.hpp>

#include <cmath>

namespace {

rg::Camera start() {
    rg::Camera c;
    c.position = {0, 1.6, 6};
    c.lookAt = {0, 0.9, 0};
    return c;
}

double distance(const rg::Camera& c) { return glm::length(c.position - c.lookAt); }

TEST(CameraControl, OrbitKeepsTheDistanceAndTheLookAtPoint) {
    rg::CameraControl control(start());
    control.orbit(120, -40);
    EXPECT_NEAR(distance(control.camera()), distance(start()), 1e-12);
    EXPECT_EQ(control.camera().lookAt, start().lookAt);
    EXPECT_GT(glm::length(control.camera().position - start().position), 0.5);
}

TEST(CameraControl, OrbitStopsShortOfThePole) {
    rg::CameraControl control(start());
    control.orbit(0, 100000);  // far past straight up or down
    glm::dvec3 toEye = glm::normalize(control.camera().position - control.camera().lookAt);
    double polar = std::acos(std::abs(glm::dot(toEye, glm::dvec3(0, 1, 0))));
    EXPECT_GT(polar, 0.005);  // up stays usable: lookAt(up) has a basis
    EXPECT_TRUE(std::isfinite(control.camera().position.x));
}

TEST(CameraControl, PanMovesEyeAndLookAtTogetherInTheImagePlane) {
    rg::CameraControl control(start());
    control.pan(100, 0, 450);
    glm::dvec3 eyeMove = control.camera().position - start().position;
    glm::dvec3 lookMove = control.camera().lookAt - start().lookAt;
    EXPECT_NEAR(glm::length(eyeMove - lookMove), 0, 1e-12);
    glm::dvec3 forward = glm::normalize(start().lookAt - start().position);
    EXPECT_NEAR(glm::dot(eyeMove, forward), 0, 1e-12);
    // 100 of 450 pixels at the look-at distance: 100/450 of the view's height there.
    double expected = 100.0 / 450 * 2 * distance(start()) * std::tan(glm::radians(45.0) / 2);
    EXPECT_NEAR(glm::length(eyeMove), expected, 1e-9);
    EXPECT_LT(eyeMove.x, 0);  // dragging right moves the view left: the scene follows the mouse
}

TEST(CameraControl, ZoomScalesTheDistanceAndResetRestores) {
    rg::CameraControl control(start());
    control.zoom(2);
    EXPECT_NEAR(distance(control.camera()), distance(start()) * 0.85 * 0.85, 1e-12);
    control.fly({1, 2, 3});
    control.reset();
    EXPECT_EQ(control.camera().position, start().position);
    EXPECT_EQ(control.camera().lookAt, start().lookAt);
}

TEST(CameraControl, FlyMovesAlongTheViewAxes) {
    rg::CameraControl control(start());
    control.fly({0, 0, 2});  // forward
    glm::dvec3 forward = glm::normalize(start().lookAt - start().position);
    EXPECT_NEAR(glm::length(control.camera().position - (start().position + 2.0 * forward)), 0, 1e-12);
    EXPECT_NEAR(distance(control.camera()), distance(start()), 1e-12);
}

// The picking ray is the ray the shader traces (camera.glsl's cameraRay
// through cameraMatrices), written from the camera's basis instead.
TEST(CameraControl, PickRayMatchesTheShadersCameraRay) {
    rg::CameraControl control(start());
    control.orbit(37, 11);
    glm::mat4 viewInverse, projInverse;
    const double w = 320, h = 180;
    rg::cameraMatrices(control.camera(), w / h, viewInverse, projInverse);
    for (auto [x, y] : {std::pair{0.0, 0.0}, {319.0, 0.0}, {160.0, 90.0}, {12.0, 170.0}}) {
        glm::vec2 ndc = (glm::vec2(float(x), float(y)) + 0.5f) / glm::vec2(w, h) * 2.0f - 1.0f;
        glm::vec4 target = projInverse * glm::vec4(ndc.x, ndc.y, 1, 1);
        glm::vec3 shader = glm::vec3(viewInverse * glm::vec4(glm::normalize(glm::vec3(target)), 0));
        glm::dvec3 pick = control.rayDirection(x, y, w, h);
        EXPECT_NEAR(glm::length(glm::dvec3(shader) - pick), 0, 1e-5) << x << "," << y;
    }
}

// One declaration, two users: the command line parses into the same
// variables the overlay edits, with the declared ranges and names.
TEST(Params, OneDeclarationDrivesTheCommandLine) {
    int depth = 3, pattern = 1;
    float epsilon = 0;
    bool accumulate = true;
    rg::Params params;
    params.integer("--depth", depth, "bounces", 0, 8);
    params.choice("--pattern", pattern, "pattern", {"uniform", "stratified", "sobol"});
    params.number("--fixed-epsilon", epsilon, "offset", 0, 0.1);
    params.toggle("--no-accumulate", accumulate, "single frames", true);
    ASSERT_EQ(params.all().size(), 4u);
    EXPECT_EQ(params.all()[3].label, "accumulate");
    EXPECT_EQ(params.all()[2].label, "fixed epsilon");

    CLI::App app;
    params.addTo(app);
    app.parse("--no-accumulate --fixed-epsilon 0.01 --pattern Sobol --depth 7", false);
    EXPECT_EQ(depth, 7);
    EXPECT_EQ(pattern, 2);
    EXPECT_FLOAT_EQ(epsilon, 0.01f);
    EXPECT_FALSE(accumulate);
    EXPECT_NE(app.help().find("(default: stratified)"), std::string::npos) << app.help();  // as declared
    EXPECT_NE(app.help().find("--pattern uniform|stratified|sobol"), std::string::npos) << app.help();  // words
    EXPECT_EQ(app.help().find("{false}"), std::string::npos) << app.help();

    CLI::App again;
    params.addTo(again);
    EXPECT_THROW(again.parse("--depth 9", false), CLI::ValidationError);
    CLI::App third;
    params.addTo(third);
    EXPECT_THROW(third.parse("--pattern halton", false), CLI::ValidationError);
}

}  // namespace
