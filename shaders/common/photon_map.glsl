// Chapter 14: the caustic photon map, read by device address (the push
// constants' photonMap): its header, the photons, the hash grid's cells.
// The photon shader writes it, the grid's compute shaders sort it, and the
// camera rays gather from it.
#ifndef PHOTON_MAP_GLSL
#define PHOTON_MAP_GLSL
#extension GL_EXT_buffer_reference : require
#extension GL_EXT_buffer_reference_uvec2 : require
#include "host_device.h"

layout(buffer_reference, std430, buffer_reference_align = 16) buffer PhotonMapRef {
    PhotonMapHeader header;
};
layout(buffer_reference, std430, buffer_reference_align = 16) buffer PhotonsRef {
    Photon photons[];
};
layout(buffer_reference, std430, buffer_reference_align = 4) buffer CellsRef {
    uint cells[];
};
// --gather-defer's requests, and each pixel's last one (gather.glsl)
layout(buffer_reference, std430, buffer_reference_align = 16) buffer RequestsRef {
    GatherRequest requests[];
};
layout(buffer_reference, std430, buffer_reference_align = 4) buffer HeadsRef {
    uint heads[];
};
layout(buffer_reference, std430, buffer_reference_align = 16) readonly buffer
EmittersRef {
    PhotonEmitter emitters[];
};

// [region hash]
// The grid's cells are cubes of twice the gathering radius; a cell's photons
// go to one of cellCount buckets by a hash of its integer coordinates
// (Teschner et al. 2003), so the grid costs memory for the photons only,
// however far the scene reaches.
ivec3 gridCell(vec3 p, float cellSize) { return ivec3(floor(p / cellSize)); }
uint cellHash(ivec3 cell, uint cellCount) {
    uvec3 u = uvec3(cell);
    return ((u.x * 73856093u) ^ (u.y * 19349663u) ^ (u.z * 83492791u)) & (cellCount - 1u);
}
// [end]
#endif
