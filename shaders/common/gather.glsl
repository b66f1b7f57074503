// Chapter 14: the caustic light at a diffuse point, from the photon map
// (density estimation, Jensen 1996): the power of the photons within the
// radius r, over the disc's area, is the irradiance they bring.
#ifndef GATHER_GLSL
#define GATHER_GLSL
#include "photon_map.glsl"

// [region gather]
// E(p) = sum of the photons' power within r of p / (pi r^2), counting only
// photons that arrived on the side n faces (a thin wall's other side is
// another surface). The 2x2x2 cells nearest p hold every photon within r
// (a cell is 2r wide); two of them may share a bucket, which is read once.
vec3 causticIrradiance(vec3 p, vec3 n) {
    if (push.photonMap == uvec2(0u)) return vec3(0.0);
    PhotonMapRef map = PhotonMapRef(push.photonMap);
    uint cellCount = map.header.cellCount;
    PhotonsRef sorted = PhotonsRef(map.header.sorted);
    CellsRef cells = CellsRef(map.header.cells);
    float r = push.photonRadius;
    ivec3 base = ivec3(floor(p / (2.0 * r) - 0.5));
    uint read[8];
    vec3 sum = vec3(0.0);
    for (uint k = 0u; k < 8u; ++k) {
        uint bucket =
            cellHash(base + ivec3(k & 1u, (k >> 1u) & 1u, k >> 2u), cellCount);
        bool again = false;
        for (uint j = 0u; j < k; ++j) again = again || read[j] == bucket;
        read[k] = bucket;
        if (again) continue;
        uint end = cells.cells[bucket];
        for (uint i = bucket == 0u ? 0u : cells.cells[bucket - 1u]; i < end; ++i) {
            Photon photon = sorted.photons[i];
            vec3 d = photon.position - p;
            if (dot(d, d) < r * r && dot(unpackSnorm4x8(photon.normal).xyz, n) > 0.0)
                sum += photon.power;
        }
    }
    return sum / (kPi * r * r);
}
// [end]
#endif
