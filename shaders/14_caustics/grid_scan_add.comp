#version 460
// Chapter 14's grid, step 4 of 4: each bucket's start within its block,
// plus where its block begins (grid_scan_blocks.comp): where the bucket's
// photons begin in the sorted array.
#extension GL_GOOGLE_include_directive : require
#include "photon_map.glsl"
layout(local_size_x = GRID_GROUP_SIZE) in;
layout(push_constant) uniform GridBlock { GridPush grid; };

void main() {
    PhotonMapRef map = PhotonMapRef(grid.photonMap);
    CellsRef cells = CellsRef(map.header.cells);
    uint i = gl_GlobalInvocationID.x;
    if (i >= map.header.cellCount) return;
    cells.cells[i] += cells.cells[map.header.cellCount + i / GRID_SCAN_BLOCK];
}
