// The CPU reference's BVH (shared/reference/geometry.cpp) must find exactly what
// testing every object finds: the same closest object at the same t, for
// rays from outside, from inside spheres, grazing and axis-parallel, on
// spheres, ellipsoids and quads.
#include <gtest/gtest.h>

#include "reference/reference.h"

#include <glm/gtc/matrix_transform.hpp>
#include <random>

namespace {

rg::Scene randomScene(size_t n, unsigned seed) {
    rg::Scene s;
    s.materials.push_back({});
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> where(-20.0, 20.0), size(0.1, 2.0);
    for (size_t i = 0; i < n; ++i) {
        rg::Object o;
        o.center = {where(rng), where(rng) * 0.2, where(rng)};
        if (i % 7 == 0) {  // a quad, tilted
            o.type = rg::ShapeType::Quad;
            o.transform = glm::rotate(glm::translate(glm::dmat4(1.0), o.center), where(rng), glm::dvec3(1, 0, 0.5)) *
                          glm::scale(glm::dmat4(1.0), glm::dvec3(size(rng), 1, size(rng)));
        } else {
            o.radius = size(rng);
            glm::dvec3 scale(o.radius);
            if (i % 5 == 0) scale.y *= 3;  // an ellipsoid
            o.transform = glm::scale(glm::translate(glm::dmat4(1.0), o.center), scale);
        }
        s.objects.push_back(o);
    }
    s.objects.push_back(s.objects[3]);  // an exact copy: hidden, as scene_file.cpp marks it
    s.objects.back().hidden = true;
    return s;
}

TEST(ReferenceBvh, FindsWhatTestingEveryObjectFinds) {
    for (size_t n : {1, 5, 100, 2000}) {
        rg::Scene scene = randomScene(n, unsigned(n));
        rg::ReferenceRenderer reference(scene);
        std::mt19937 rng(7);
        std::uniform_real_distribution<double> where(-25.0, 25.0), unit(-1.0, 1.0);
        int hits = 0;
        for (int k = 0; k < 20000; ++k) {
            glm::dvec3 origin(where(rng), where(rng) * 0.3, where(rng));
            if (k % 4 == 0) origin = scene.objects[size_t(k) % scene.objects.size()].center;  // inside a sphere
            glm::dvec3 direction(unit(rng), unit(rng), unit(rng));
            if (k % 10 == 0) direction = glm::dvec3(k % 3 == 0, k % 3 == 1, k % 3 == 2);  // axis-parallel
            if (glm::length(direction) < 1e-3) continue;
            direction = glm::normalize(direction);
            rg::ReferenceHit fast = reference.trace(origin, direction, 1e-6, 1e30);
            rg::ReferenceHit all = reference.traceLinear(origin, direction, 1e-6, 1e30);
            ASSERT_EQ(fast.t, all.t) << "n " << n << " ray " << k;
            if (all.t >= 0) {
                ASSERT_EQ(fast.object, all.object) << "n " << n << " ray " << k;
                EXPECT_EQ(fast.normal, all.normal);
                ++hits;
            }
            // A shadow ray's bounded interval too.
            double limit = std::max(0.0, all.t >= 0 ? all.t * 0.999 : 10.0);
            EXPECT_EQ(reference.trace(origin, direction, 1e-6, limit).t,
                      reference.traceLinear(origin, direction, 1e-6, limit).t);
        }
        EXPECT_GT(hits, 1000 / int(n == 1 ? 100 : 1)) << n;  // the rays do hit things
    }
}

}  // namespace
