#version 460
// Chapter 14's grid, step 2 of 3: the buckets' counts become where each
// bucket's photons begin (an exclusive prefix sum), in one workgroup: each
// invocation sums a run of buckets, the runs' sums are added up in shared
// memory, and each invocation writes its run's starts.
#extension GL_GOOGLE_include_directive : require
#include "photon_map.glsl"
layout(local_size_x = GRID_GROUP_SIZE) in;
layout(push_constant) uniform GridBlock { GridPush grid; };

shared uint runStart[GRID_GROUP_SIZE];

void main() {
    PhotonMapRef map = PhotonMapRef(grid.photonMap);
    CellsRef cells = CellsRef(map.header.cells);
    // cellCount is a power of two of at least 1024: every run is as long
    uint length = map.header.cellCount / GRID_GROUP_SIZE;
    uint first = gl_LocalInvocationID.x * length;
    uint sum = 0u;
    for (uint i = 0u; i < length; ++i) sum += cells.cells[first + i];
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
    for (uint i = 0u; i < length; ++i) {
        uint count = cells.cells[first + i];
        cells.cells[first + i] = start;
        start += count;
    }
}
