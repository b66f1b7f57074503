// The sphere intersection shader's own code (shaders/common/sphere_intersect.glsl),
// compiled here as C++ in float, against double precision on the rays that
// break naive formulas: a small sphere far away, nearly tangent rays, an
// origin on the surface, an origin inside.
#include <gtest/gtest.h>

#include "reference.h"

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
    bool hit = shader::intersectUnitSphere(o, d, t);
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

TEST(SphereIntersection, MissesWhatItShould) {
    EXPECT_FALSE(gpu({0, 2, -5}, {0, 0, 1}).hit);
    EXPECT_FALSE(gpu({3, 3, 3}, glm::normalize(glm::vec3(1, 0, 0))).hit);
}

}  // namespace
