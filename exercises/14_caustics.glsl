// Exercise, chapter 14: density estimation, the photons' light at a point.
// replaces: common/gather.glsl#gather
// The irradiance at p is the power of the photons within the radius r
// (push.photonRadius) over the disc's area, pi r^2, counting only photons
// that arrived on the side n faces (unpackSnorm4x8(photon.normal).xyz . n > 0).
// The grid: photons sit in cubes 2r wide (gridCell), each cube in the
// bucket cellHash gives; after the scatter, bucket b's photons are
// sorted.photons[b == 0 ? 0 : cells.cells[b - 1]] up to cells.cells[b]. The
// 2x2x2 cubes nearest p, from floor(p / (2r) - 0.5), hold every photon
// within r; read a bucket that two of them share once. (`scale`, what the
// caller multiplies E by, is for a performance trick: leave it unused.)
// Until it is written, every shadow of glass is black.
vec3 causticIrradiance(vec3 p, vec3 n, vec3 scale) {
    if (push.photonMap == uvec2(0u)) return vec3(0.0);
    PhotonMapRef map = PhotonMapRef(push.photonMap);
    uint cellCount = map.header.cellCount;
    PhotonsRef sorted = PhotonsRef(map.header.sorted);
    CellsRef cells = CellsRef(map.header.cells);
    float r = push.photonRadius;
    // TODO(you): sum the photons' power within r of p, over pi r^2
    return vec3(0.0);
}
