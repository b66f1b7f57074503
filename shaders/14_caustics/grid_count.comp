#version 460
// Chapter 14's grid, step 1 of 3: each stored photon counts itself in its
// cell's bucket.
#extension GL_GOOGLE_include_directive : require
#include "photon_map.glsl"
layout(local_size_x = GRID_GROUP_SIZE) in;
layout(push_constant) uniform GridBlock { GridPush grid; };

void main() {
    PhotonMapRef map = PhotonMapRef(grid.photonMap);
    uint i = gl_GlobalInvocationID.x;
    if (i >= min(map.header.stored, map.header.capacity)) return;
    vec3 p = PhotonsRef(map.header.photons).photons[i].position;
    uint bucket = cellHash(gridCell(p, grid.cellSize), map.header.cellCount);
    atomicAdd(CellsRef(map.header.cells).cells[bucket], 1u);
}
