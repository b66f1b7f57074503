#version 460
// Chapter 02: chapter 01's pattern, animated. The checker squares scroll to
// the right by PATTERN_SCROLL pixels per second of animation time, so a frame
// that read a half-written target (a missing barrier) would show a tear.
#extension GL_GOOGLE_include_directive : require
#include "host_device.h"

layout(local_size_x = PATTERN_GROUP_SIZE, local_size_y = PATTERN_GROUP_SIZE) in;
layout(binding = PATTERN_BINDING_TARGET, rgba32f) uniform writeonly image2D target;
layout(push_constant) uniform Push { PatternPush pc; };

void main() {
    uvec2 pixel = gl_GlobalInvocationID.xy;
    if (pixel.x >= pc.width || pixel.y >= pc.height) return;
    vec2 uv = (vec2(pixel) + 0.5) / vec2(pc.width, pc.height);
    uint shift = uint(pc.time * PATTERN_SCROLL);  // whole pixels: exact, testable
    uint x = pixel.x + pc.width * pc.checker - shift % (pc.width * pc.checker);
    bool odd = ((x / pc.checker + pixel.y / pc.checker) & 1u) == 1u;
    imageStore(target, ivec2(pixel), vec4(uv.x, uv.y, odd ? 0.75 : 0.25, 1.0));
}
