#version 460
// Chapter 03: the TLAS's view of the world from above. Each instance's
// world-space box (its unit shape's box through its transform, as the TLAS
// bounds it) is drawn in the instance's colour, the smallest on top, read
// from the very buffer the TLAS is built and refitted from.
#extension GL_GOOGLE_include_directive : require
#include "host_device.h"

layout(local_size_x = PATTERN_GROUP_SIZE, local_size_y = PATTERN_GROUP_SIZE) in;
layout(binding = FOOTPRINT_BINDING_TARGET, rgba32f) uniform writeonly image2D target;
layout(binding = FOOTPRINT_BINDING_INSTANCES, std430) readonly buffer Instances {
    InstanceRecord instances[];
};
layout(push_constant) uniform Push { FootprintPush pc; };

void main() {
    uvec2 pixel = gl_GlobalInvocationID.xy;
    if (pixel.x >= pc.width || pixel.y >= pc.height) return;
    vec2 uv = (vec2(pixel) + 0.5) / vec2(pc.width, pc.height);
    // (x, z), z grows downward in the image
    vec2 world = pc.bounds.xy + uv * pc.bounds.zw;
    vec3 color = vec3(0.05);
    // 1-unit grid
    if (fract(world.x) < 0.02 || fract(world.y) < 0.02) color = vec3(0.15);
    // Where boxes overlap, the smallest shows: the floor's box holds every
    // sphere's, and drawn over them it would hide them all.
    float smallest = 1e30;
    for (uint i = 0; i < pc.instanceCount; ++i) {
        InstanceRecord r = instances[i];
        // Box of [-1,1]^3 through the affine transform: centre = translation,
        // half-size = sum of |matrix| rows.
        vec2 center = vec2(r.row0.w, r.row2.w);
        vec2 half_ = vec2(dot(abs(r.row0.xyz), vec3(1)), dot(abs(r.row2.xyz), vec3(1)));
        vec2 d = abs(world - center);
        if (all(lessThanEqual(d, half_)) && half_.x * half_.y < smallest) {
            smallest = half_.x * half_.y;
            color = instanceColor(r.customIndexAndMask & 0xFFFFFFu);
            // outline
            if (any(greaterThan(d, half_ - pc.bounds.z / float(pc.width) * 1.5)))
                color *= 0.5;
        }
    }
    imageStore(target, ivec2(pixel), vec4(color, 1.0));
}
