#version 460
// Chapter 14's grid, step 3 of 3: each photon takes the next place of its
// bucket in the sorted array. Afterwards each bucket's entry holds where its
// photons end, which is where the next bucket's begin.
#extension GL_GOOGLE_include_directive : require
#include "photon_map.glsl"
layout(local_size_x = GRID_GROUP_SIZE) in;
layout(push_constant) uniform GridBlock { GridPush grid; };

void main() {
    PhotonMapRef map = PhotonMapRef(grid.photonMap);
    uint i = gl_GlobalInvocationID.x;
    if (i >= min(map.header.stored, map.header.capacity)) return;
    Photon photon = PhotonsRef(map.header.photons).photons[i];
    ivec3 cell = gridCell(photon.position, grid.cellSize);
    uint bucket = cellHash(cell, map.header.cellCount);
    uint place = atomicAdd(CellsRef(map.header.cells).cells[bucket], 1u);
    PhotonsRef(map.header.sorted).photons[place] = photon;
}
