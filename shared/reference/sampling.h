// The shaders' sample points (shaders/common/sampling.glsl) compiled as C++,
// with GLM for GLSL's types. The CPU reference integrates over the very
// points the GPU drew (chapter 04's antialiasing: where in each pixel), the
// way chapter 13's reference follows the GPU's wavelengths; the unit tests
// check their stratification (tests/test_sampling.cpp).
#pragma once
#include <cmath>
#include <cstdint>
#include <glm/glm.hpp>

namespace shader {
namespace {  // each file that includes it gets its own copy: none to clash at link time
using namespace glm;
using std::sqrt;
using uint = std::uint32_t;
const float kPi = 3.14159265358979323846f;
// A file that includes this calls some of the shader file's functions, not
// all of them; the rest are not a mistake here.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-function"
#include "sampling.glsl"
#pragma GCC diagnostic pop
}  // namespace
}  // namespace shader
