// The sphere intersection shader's own code (shaders/common/sphere_intersect.glsl),
// compiled here as C++ in float, against double precision on the rays that
// break naive formulas: a small sphere far away, nearly tangent rays, an
// origin on the surface, an origin inside.
#include <gtest/gtest.h>

#include "reference/reference.h"

#include <cmath>
#include <glm/glm.hpp>

#include "glsl_as_cpp.h"

namespace {

struct Roots {
    bool hit;
    double t0, t1;
};

Roots exact(const glm::dvec3& o, const glm::dvec3& d) {
    Roots r{};
    r.hit = rg::referenceUnitSphere(o, d, r.t0, r.t1);
    return r;
}

Roots gpu(const glm::vec3& o, const glm::vec3& d) {
    glm::vec2 t;
    bool hit = shader::intersectSphere(o, d, glm::vec3(0.0f), 1.0f, t);
    return {hit, t.x, t.y};
}

// The float inputs, promoted exactly, are what double precision solves: the
// test measures the shader's arithmetic, not the rounding of its inputs.
void expectClose(const glm::vec3& o, const glm::vec3& d, double relTolerance, double absTolerance) {
    Roots want = exact(glm::dvec3(o), glm::dvec3(d));
    Roots got = gpu(o, d);
    ASSERT_EQ(got.hit, want.hit) << "o=(" << o.x << "," << o.y << "," << o.z << ")";
    if (!want.hit) return;
    EXPECT_NEAR(got.t0, want.t0, relTolerance * std::abs(want.t0) + absTolerance);
    EXPECT_NEAR(got.t1, want.t1, relTolerance * std::abs(want.t1) + absTolerance);
}

TEST(SphereIntersection, SmallSphereFarAway) {
    // 1e5 radii away (a sphere of radius 1e-3 seen from 100 units): the naive
    // b*b - a*c loses every digit of the discriminant here.
    for (double y : {0.0, 0.3, 0.7, 0.99}) {
        glm::vec3 o(0.1f, float(y), 1e5f), d(0, 0, -1);
        expectClose(o, d, 4e-7, 0);
        Roots got = gpu(o, d);
        EXPECT_TRUE(got.hit);
    }
    // Same with an unnormalized direction, as object space gives it (scale 1e3).
    expectClose({0.2f, -0.4f, 1e5f}, {0, 0, -1e3f}, 4e-7, 0);
}

TEST(SphereIntersection, NearlyTangentRays) {
    for (double eps : {1e-2, 1e-3, 1e-4}) {
        expectClose({0, float(1 - eps), -10}, {0, 0, 1}, 1e-6, 2e-4);  // just inside the silhouette: hit
        Roots miss = gpu({0, float(1 + eps), -10}, {0, 0, 1});          // just outside: miss
        EXPECT_FALSE(miss.hit) << eps;
    }
}

TEST(SphereIntersection, OriginOnTheSurface) {
    glm::vec3 o = glm::normalize(glm::vec3(1, 2, 3));  // on the sphere, to float precision
    Roots inward = gpu(o, -o);
    ASSERT_TRUE(inward.hit);
    EXPECT_NEAR(inward.t0, 0.0, 1e-6);  // the surface it starts on
    EXPECT_NEAR(inward.t1, 2.0, 1e-6);  // the far side, through the centre
    Roots outward = gpu(o, o);
    ASSERT_TRUE(outward.hit);
    EXPECT_NEAR(outward.t1, 0.0, 1e-6);
    EXPECT_NEAR(outward.t0, -2.0, 1e-6);
    expectClose(o, glm::normalize(glm::vec3(-1, 0.5f, 0.2f)), 1e-6, 1e-6);
}

TEST(SphereIntersection, OriginInside) {
    Roots r = gpu({0.1f, 0.2f, 0.3f}, {0, 0, 1});
    ASSERT_TRUE(r.hit);
    EXPECT_LT(r.t0, 0.0);
    EXPECT_GT(r.t1, 0.0);
    expectClose({0.1f, 0.2f, 0.3f}, {0, 0, 1}, 1e-6, 1e-7);
}

// A floor as the top of a sphere of radius R (chapter 06), the eye h above it:
// the hit point o + t d must lie on the float sphere as exactly as on a
// plane, and a ray leaving it upward from just above must not hit it again.
// Both directions point below every horizon here (5.7 degrees and more).
TEST(SphereIntersection, BigSphereSeenFromNearItsSurface) {
    for (float radius : {1e3f, 1e4f, 1e5f, 1e6f})
        for (float h : {1.5f, 0.01f})
            for (glm::vec3 dir : {glm::vec3(0.1f, -0.5f, -0.8f), glm::vec3(0.02f, -0.1f, -1.0f)}) {
                glm::vec3 centre(0, -radius, 0), o(0.3f, h, 2.0f), d = glm::normalize(dir);
                glm::vec2 t;
                ASSERT_TRUE(shader::intersectSphere(o, d, centre, radius, t)) << radius;
                glm::dvec3 p = glm::dvec3(o) + double(t.x) * glm::dvec3(d);
                double fromSurface = glm::length(p - glm::dvec3(centre)) - radius;
                EXPECT_LE(std::abs(fromSurface), 1e-6 * (glm::length(glm::dvec3(o)) + t.x))
                    << "R " << radius << ", h " << h << ": " << fromSurface;
                glm::vec3 above = glm::vec3(p) + glm::vec3(0, 1e-5f * (1 + t.x), 0);
                if (shader::intersectSphere(above, glm::normalize(glm::vec3(-0.3f, 1, 0.2f)), centre, radius, t)) {
                    EXPECT_LT(t.y, 0.0f) << "R " << radius << ": the ray leaving the floor hits it again";
                }
            }
}

// A sky dome of radius 1e20 seen from inside, in world space and as an
// instance of the unit sphere (whose object-space direction is 1e-20 long):
// r^2 and |d|^2 are past float's range, the roots are not.
TEST(SphereIntersection, HugeDomeFromInside) {
    glm::vec3 d = glm::normalize(glm::vec3(0.3f, 0.8f, -0.5f));
    glm::vec2 t;
    ASSERT_TRUE(shader::intersectSphere(glm::vec3(1, 2, 3), d, glm::vec3(0), 1e20f, t));
    EXPECT_NEAR(t.y / 1e20, 1.0, 1e-6);
    EXPECT_NEAR(t.x / 1e20, -1.0, 1e-6);
    ASSERT_TRUE(shader::intersectSphere(glm::vec3(1e-20f, 2e-20f, 3e-20f), d * 1e-20f, glm::vec3(0), 1.0f, t));
    EXPECT_NEAR(t.y / 1e20, 1.0, 1e-6);  // t in the direction's own units
}

TEST(SphereIntersection, MissesWhatItShould) {
    EXPECT_FALSE(gpu({0, 2, -5}, {0, 0, 1}).hit);
    EXPECT_FALSE(gpu({3, 3, 3}, glm::normalize(glm::vec3(1, 0, 0))).hit);
}

}  // namespace
