#version 460
// Chapter 14, --gather-defer's second step: each pixel adds the light of
// its deferred gathers (gather_deferred.comp) to the picture, as the camera
// rays would have: times the exposure, over the frames averaged.
#extension GL_GOOGLE_include_directive : require
#include "photon_map.glsl"
layout(local_size_x = 8, local_size_y = 8) in;
layout(push_constant) uniform DeferBlock { DeferPush defer; };
layout(binding = RT_BINDING_TARGET, rgba32f) uniform image2D target;

void main() {
    ivec2 size = imageSize(target);
    uvec2 xy = gl_GlobalInvocationID.xy;
    if (xy.x >= uint(size.x) || xy.y >= uint(size.y)) return;
    PhotonMapRef map = PhotonMapRef(defer.photonMap);
    RequestsRef requests = RequestsRef(map.header.requests);
    uint q = HeadsRef(map.header.heads).heads[xy.y * uint(size.x) + xy.x];
    if (q == ~0u) return;
    vec3 light = vec3(0.0);
    for (; q != ~0u; q = requests.requests[q].next) light += requests.requests[q].scale;
    vec4 pixel = imageLoad(target, ivec2(xy));
    imageStore(target, ivec2(xy), vec4(pixel.rgb + light * defer.resolveScale, pixel.a));
}
