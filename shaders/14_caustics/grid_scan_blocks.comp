#version 460
// Chapter 14's grid, step 3 of 4: the blocks' totals (after the buckets,
// grid_scan.comp) become where each block begins, in one workgroup: a few
// thousand totals at most (cellCount / GRID_SCAN_BLOCK), each invocation a
// run of them, the runs added up in shared memory.
#extension GL_GOOGLE_include_directive : require
#include "photon_map.glsl"
layout(local_size_x = GRID_GROUP_SIZE) in;
layout(push_constant) uniform GridBlock { GridPush grid; };

shared uint runStart[GRID_GROUP_SIZE];

void main() {
    PhotonMapRef map = PhotonMapRef(grid.photonMap);
    CellsRef cells = CellsRef(map.header.cells);
    uint blocks = map.header.cellCount / GRID_SCAN_BLOCK;
    // blocks is a power of two; below GRID_GROUP_SIZE some runs are empty
    uint length = (blocks + GRID_GROUP_SIZE - 1u) / GRID_GROUP_SIZE;
    uint first = gl_LocalInvocationID.x * length;
    uint end = min(first + length, blocks);
    uint base = map.header.cellCount;
    uint sum = 0u;
    for (uint i = first; i < end; ++i) sum += cells.cells[base + i];
    runStart[gl_LocalInvocationID.x] = sum;
    barrier();
    if (gl_LocalInvocationID.x == 0u) {
        uint total = 0u;
        for (uint k = 0u; k < GRID_GROUP_SIZE; ++k) {
            uint count = runStart[k];
            runStart[k] = total;
            total += count;
        }
    }
    barrier();
    uint start = runStart[gl_LocalInvocationID.x];
    for (uint i = first; i < end; ++i) {
        uint count = cells.cells[base + i];
        cells.cells[base + i] = start;
        start += count;
    }
}
