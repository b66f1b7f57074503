// The descriptor set every ray tracing chapter binds (host_device.h).
#ifndef RT_BINDINGS_GLSL
#define RT_BINDINGS_GLSL
#extension GL_EXT_ray_tracing : require
#include "host_device.h"

// [region tlas]
layout(binding = RT_BINDING_TLAS) uniform accelerationStructureEXT tlas;
// [end]
layout(binding = RT_BINDING_CAMERA, std140) uniform CameraBlock { RtCamera camera; };
layout(binding = RT_BINDING_OBJECTS, std430) readonly buffer Objects {
    GpuObject objects[];
};
layout(binding = RT_BINDING_MATERIALS, std430) readonly buffer Materials {
    GpuMaterial materials[];
};
layout(binding = RT_BINDING_LIGHTS, std430) readonly buffer Lights { GpuLight lights[]; };
layout(binding = RT_BINDING_SKY, std430) readonly buffer Sky { vec4 skyTexels[]; };
layout(push_constant) uniform PushBlock { RtPush push; };
// [region averages]
// Specialization constant 1 (rt_pipeline.h's raygenAverages): false for a
// run that never averages frames (headless, --antialias off, chapter 11's
// --no-accumulate). The jitter and the running mean are then compiled out;
// merely being there, untaken, they cost 2-3 % of a frame on an H200.
layout(constant_id = 1) const bool kAverages = true;
// [end]
// [region careful_numerics]
// Specialization constants 2 and 3 (rt_pipeline.h's carefulSizes and
// carefulShininess): the branches that keep huge and tiny scenes exact (a
// floor sphere of radius 1e5, a sky dome of 1e20) and huge exponents exact
// (a shininess of 1e6) cost up to 8 % of a frame on an H200 even where
// they are never taken. The host compiles them in only for a scene that
// needs them (rt_scene.h's carefulNumerics).
layout(constant_id = 2) const bool kCarefulSizes = true;
layout(constant_id = 3) const bool kCarefulShininess = true;
// [end]
// [region alpha_test]
// Specialization constant 4 (rt_pipeline.h's alphaTest): true only for a
// scene with an alpha-tested material (chapter 12's any-hit shader,
// alpha.rahit). Else every ray is traced with the opaque flag, as before:
// the traversal then never even looks for an any-hit shader.
layout(constant_id = 4) const bool kAlphaTest = false;
const uint kRayFlags = kAlphaTest ? gl_RayFlagsNoneEXT : gl_RayFlagsOpaqueEXT;
// [end]
// Specialization constant 5 (rt_pipeline.h's thinWalls): true only for a
// scene with a thin-walled material (MATERIAL_THIN). The ray tree's thin
// branches cost chapter 10 1.6 % of a frame on an H200 (3 % with 10^6
// spheres) where no material is thin (docs/performance.md).
layout(constant_id = 5) const bool kThinWalls = true;
// Specialization constant 6 (rt_pipeline.h's rayCones): true only for a
// scene with a mip-mapped texture (chapter 12): rays then carry their cone
// (raygen_common.glsl's traceClosest) and hits choose a level (mesh.rchit).
layout(constant_id = 6) const bool kRayCones = false;
// Specialization constant 7 (rt_pipeline.h's sunDiscs): true only for a
// scene with a sun of some size (radiometry.glsl's towardLight, chapter 14).
layout(constant_id = 7) const bool kSunDiscs = false;
// Specialization constant 8 (rt_pipeline.h's meshes): true only for a
// scene with triangle meshes (chapter 12), the one shape whose shading
// normal differs from its surface's. Else no hit writes the payload's
// shading normal and no ray generation shader reads it (what that saves:
// docs/performance.md, chapter 10).
layout(constant_id = 8) const bool kMeshes = true;

const float kPi = 3.14159265358979323846;
const float kInfinity = 3.0e38;
#endif
