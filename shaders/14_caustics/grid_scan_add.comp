#version 460
// Chapter 14's grid, step 4 of 4: each bucket's start within its block,
// plus where its block begins (grid_scan_blocks.comp): where the bucket's
// photons begin in the sorted array. One workgroup a block, each invocation
// a run, as in grid_scan.comp: cellCount / GRID_SCAN_BLOCK workgroups stay
// far below maxComputeWorkGroupCount (65,535 at least) at every --photons.
#extension GL_GOOGLE_include_directive : require
#include "photon_map.glsl"
layout(local_size_x = GRID_GROUP_SIZE) in;
layout(push_constant) uniform GridBlock { GridPush grid; };

void main() {
    PhotonMapRef map = PhotonMapRef(grid.photonMap);
    CellsRef cells = CellsRef(map.header.cells);
    uint blockStart = cells.cells[map.header.cellCount + gl_WorkGroupID.x];
    uint first =
        gl_WorkGroupID.x * GRID_SCAN_BLOCK + gl_LocalInvocationID.x * GRID_SCAN_RUN;
    for (uint i = 0u; i < GRID_SCAN_RUN; ++i) cells.cells[first + i] += blockStart;
}
