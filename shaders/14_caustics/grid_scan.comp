#version 460
// Chapter 14's grid, step 2 of 4: the buckets' counts become where each
// bucket's photons begin (an exclusive prefix sum), a block of
// GRID_SCAN_BLOCK buckets per workgroup: each invocation sums a run of
// GRID_SCAN_RUN buckets, the runs' sums are added up in shared memory, and
// each invocation writes its run's starts within the block. The block's
// total goes after the buckets, for step 3 (grid_scan_blocks.comp).
#extension GL_GOOGLE_include_directive : require
#include "photon_map.glsl"
layout(local_size_x = GRID_GROUP_SIZE) in;
layout(push_constant) uniform GridBlock { GridPush grid; };

shared uint runStart[GRID_GROUP_SIZE];

void main() {
    PhotonMapRef map = PhotonMapRef(grid.photonMap);
    CellsRef cells = CellsRef(map.header.cells);
    uint first =
        gl_WorkGroupID.x * GRID_SCAN_BLOCK + gl_LocalInvocationID.x * GRID_SCAN_RUN;
    uint sum = 0u;
    for (uint i = 0u; i < GRID_SCAN_RUN; ++i) sum += cells.cells[first + i];
    runStart[gl_LocalInvocationID.x] = sum;
    barrier();
    if (gl_LocalInvocationID.x == 0u) {
        uint total = 0u;
        for (uint k = 0u; k < GRID_GROUP_SIZE; ++k) {
            uint count = runStart[k];
            runStart[k] = total;
            total += count;
        }
        cells.cells[map.header.cellCount + gl_WorkGroupID.x] = total;
    }
    barrier();
    uint start = runStart[gl_LocalInvocationID.x];
    for (uint i = 0u; i < GRID_SCAN_RUN; ++i) {
        uint count = cells.cells[first + i];
        cells.cells[first + i] = start;
        start += count;
    }
}
