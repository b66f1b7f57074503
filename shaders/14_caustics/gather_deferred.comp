#version 460
// Chapter 14, --gather-defer (gather.glsl's gather_defer; a performance
// trick the performance page measures): the crowded cells' gathers the
// camera rays left behind. A workgroup takes one request at a time, its
// invocations read every 64th photon of the cell each, with the camera
// rays' own test, and the workgroup sums their powers. The request then
// holds the light it brings to its pixel: scale * E.
#extension GL_GOOGLE_include_directive : require
#include "photon_map.glsl"
layout(local_size_x = DEFER_GROUP_SIZE) in;
layout(push_constant) uniform DeferBlock { DeferPush defer; };

const float kPi = 3.14159265358979323846;
shared vec3 partial[DEFER_GROUP_SIZE];

void main() {
    PhotonMapRef map = PhotonMapRef(defer.photonMap);
    PhotonsRef sorted = PhotonsRef(map.header.sorted);
    CellsRef cells = CellsRef(map.header.cells);
    RequestsRef requests = RequestsRef(map.header.requests);
    uint total = min(map.header.deferred, map.header.deferCapacity);
    float r = defer.radius;
    uint lane = gl_LocalInvocationID.x;
    // q is the same for the whole workgroup: its barriers are met by all
    for (uint q = gl_WorkGroupID.x; q < total; q += gl_NumWorkGroups.x) {
        GatherRequest request = requests.requests[q];
        uint first = request.bucket == 0u ? 0u : cells.cells[request.bucket - 1u];
        uint count = cells.cells[request.bucket] - first;
        vec3 sum = vec3(0.0);
        for (uint i = lane; i < count; i += DEFER_GROUP_SIZE) {
            Photon photon = sorted.photons[first + i];
            vec3 d = photon.position - request.position;
            if (dot(d, d) < r * r &&
                dot(unpackSnorm4x8(photon.normal).xyz, request.normal) > 0.0)
                sum += photon.power;
        }
        partial[lane] = sum;
        barrier();
        for (uint half_ = DEFER_GROUP_SIZE / 2u; half_ > 0u; half_ /= 2u) {
            if (lane < half_) partial[lane] += partial[lane + half_];
            barrier();
        }
        if (lane == 0u)
            requests.requests[q].scale = request.scale * partial[0] / (kPi * r * r);
        barrier();  // partial[0] read before the next request overwrites it
    }
}
