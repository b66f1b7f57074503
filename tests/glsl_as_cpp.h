// The shaders' plain-GLSL files compiled as C++ (GLM supplies GLSL's types
// and functions), so that the unit tests check the very code the GPU runs.
#pragma once
#include "reference/sampling.h"  // sampling.glsl, which the CPU reference uses too

namespace shader {
#define RG_OUT(T) T&  // GLSL's `out` parameters
#define RG_PRECISE    // C++ already evaluates as written (no -ffast-math)
// rt_bindings.glsl's specialization constant; a test may switch it off
inline bool kCarefulSizes = true;
#include "fresnel.glsl"
#include "microfacet.glsl"
#include "sphere_intersect.glsl"
#undef RG_OUT
#undef RG_PRECISE
}  // namespace shader
