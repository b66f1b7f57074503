// Chapter 14: the caustic light at a diffuse point, from the photon map
// (density estimation, Jensen 1996): the power of the photons within the
// radius r, over the disc's area, is the irradiance they bring.
#ifndef GATHER_GLSL
#define GATHER_GLSL
#include "photon_map.glsl"
#include "raygen_common.glsl"  // the target: its width numbers the pixels
#include "sampling.glsl"

// [region gather_cap]
// Performance (the performance page measures it; --gather-cap 0 turns it
// off): where a caustic focuses, one cell can hold a good part of all the
// photons, and every pixel there would read them all. A gather reads at
// most push.gatherCap of a cell's photons instead: a run of consecutive
// ones from a random start, wrapping around, weighted by count / cap. Each
// photon is read with probability cap / count, so the estimate's mean is
// unchanged (unbiased); it only adds noise where photons are dense, and
// the frames' average removes it as it removes the photons' own noise.
struct CellRun {
    uint start, count;
    float weight;
};
CellRun cellRun(uint count, vec3 p, uint bucket) {
    if (push.gatherCap == 0u || count <= push.gatherCap) return CellRun(0u, count, 1.0);
    uvec3 bits = floatBitsToUint(p);
    uint h = pcgHash(bits.x ^ pcgHash(bits.y ^ pcgHash(bits.z ^ pcgHash(push.frame ^
                                                                         bucket))));
    return CellRun(h % count, push.gatherCap, float(count) / float(push.gatherCap));
}
// [end]

// [region gather_defer]
// Performance (the performance page measures it; --gather-defer 0 turns it
// off): the pixels where a caustic focuses read thousands of photons each,
// one after another, while the rest of the GPU has finished and waits for
// them. A cell holding more than push.gatherDefer photons is instead left
// to a compute pass after the camera rays (gather_deferred.comp), where 64
// invocations share each such cell's photons: the same photons, the same
// test, the same sum (in another order). The pass adds scale times their
// irradiance to the pixel. Off with --gather-cap, which reads a run instead.
bool deferGather(uint count, vec3 p, vec3 n, vec3 scale, uint bucket) {
    if (push.gatherDefer == 0u || push.gatherCap != 0u || count <= push.gatherDefer)
        return false;
    PhotonMapRef map = PhotonMapRef(push.photonMap);
    uint q = atomicAdd(map.header.deferred, 1u);
    if (q >= map.header.deferCapacity) return false;  // full: gathered here instead
    uint pixel = gl_LaunchIDEXT.y * uint(imageSize(target).x) + gl_LaunchIDEXT.x;
    uint next = atomicExchange(HeadsRef(map.header.heads).heads[pixel], q);
    RequestsRef(map.header.requests).requests[q] =
        GatherRequest(p, bucket, n, pixel, scale, next);
    return true;
}
// [end]

// [region gather]
// E(p) = sum of the photons' power within r of p / (pi r^2), counting only
// photons that arrived on the side n faces (a thin wall's other side is
// another surface). The 2x2x2 cells nearest p hold every photon within r
// (a cell is 2r wide); two of them may share a bucket, which is read once.
// cellRun gives all of a cell's photons, or a random run of a crowded
// cell's, weighted up (gather_cap above: a performance trick). `scale` is
// what the caller multiplies E by: a crowded cell left to a later pass
// (gather_defer above, another) brings its light to the pixel with it.
vec3 causticIrradiance(vec3 p, vec3 n, vec3 scale) {
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
        uint first = bucket == 0u ? 0u : cells.cells[bucket - 1u];
        uint count = cells.cells[bucket] - first;
        if (deferGather(count, p, n, scale, bucket)) continue;
        CellRun run = cellRun(count, p, bucket);
        vec3 cellSum = vec3(0.0);
        uint j = 0u;
        // [region gather_batch]
        // Performance (the performance page measures it): where a caustic
        // focuses, this loop runs thousands of times, and each pass waits for
        // its photon's load. Four loads asked for at once, then tested in the
        // same order: the same sum, one wait per four photons. Chapter 15
        // leaves it out: its frame took 7 % longer with it (the same page).
#ifndef MICROFACET
        for (; j + 4u <= run.count; j += 4u) {
            Photon batch[4];
            for (uint b = 0u; b < 4u; ++b) {
                uint i = run.start + j + b;
                batch[b] = sorted.photons[first + (i < count ? i : i - count)];
            }
            for (uint b = 0u; b < 4u; ++b) {
                vec3 d = batch[b].position - p;
                if (dot(d, d) < r * r &&
                    dot(unpackSnorm4x8(batch[b].normal).xyz, n) > 0.0)
                    cellSum += batch[b].power;
            }
        }
#endif
        // [end]
        for (; j < run.count; ++j) {
            uint i = run.start + j;
            Photon photon = sorted.photons[first + (i < count ? i : i - count)];
            vec3 d = photon.position - p;
            if (dot(d, d) < r * r && dot(unpackSnorm4x8(photon.normal).xyz, n) > 0.0)
                cellSum += photon.power;
        }
        sum += cellSum * run.weight;
    }
    return sum / (kPi * r * r);
}
// [end]
#endif
