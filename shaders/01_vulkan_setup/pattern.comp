#version 460
// Chapter 01: one invocation per pixel writes a pattern whose every value is
// known (the test recomputes it): red grows to the right, green downward,
// blue alternates in checker squares.
#extension GL_GOOGLE_include_directive : require
#include "host_device.h"

// [region shader]
layout(local_size_x = PATTERN_GROUP_SIZE, local_size_y = PATTERN_GROUP_SIZE) in;
layout(binding = PATTERN_BINDING_TARGET, rgba32f) uniform writeonly image2D target;
layout(push_constant) uniform Push { PatternPush pc; };

void main() {
    uvec2 pixel = gl_GlobalInvocationID.xy;
    if (pixel.x >= pc.width || pixel.y >= pc.height) return;  // the last groups overhang
    vec2 uv = (vec2(pixel) + 0.5) / vec2(pc.width, pc.height);  // pixel centres
    bool odd = ((pixel.x / pc.checker + pixel.y / pc.checker) & 1u) == 1u;
    imageStore(target, ivec2(pixel), vec4(uv.x, uv.y, odd ? 0.75 : 0.25, 1.0));
}
// [end]
