// The shaders' plain-GLSL files compiled as C++ (GLM supplies GLSL's types
// and functions), so that the unit tests check the very code the GPU runs.
#pragma once
#include <cmath>
#include <cstdint>
#include <glm/glm.hpp>

namespace shader {
using namespace glm;
using std::sqrt;
using uint = std::uint32_t;
const float kPi = 3.14159265358979323846f;
#define RG_OUT(T) T&  // GLSL's `out` parameters
#define RG_PRECISE    // C++ already evaluates as written (no -ffast-math)
#include "fresnel.glsl"
#include "sampling.glsl"
#include "sphere_intersect.glsl"
#undef RG_OUT
#undef RG_PRECISE
}  // namespace shader
