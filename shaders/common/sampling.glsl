// Sample points for rough reflections (chapter 11) and inside pixels
// (chapter 04's antialiasing), deterministic: the same pixel, frame and
// sample index always give the same point, so a run can be repeated
// exactly. Plain GLSL that also compiles as C++ (shared/reference/sampling.h).
#ifndef SAMPLING_GLSL
#define SAMPLING_GLSL
#define PATTERN_UNIFORM 0u     // independent random points
#define PATTERN_STRATIFIED 1u  // one jittered point per cell of a sqrt(N) x sqrt(N) grid
// low-discrepancy (i/N, radical inverse of i), rotated per pixel
#define PATTERN_HAMMERSLEY 2u
// one Owen-scrambled Sobol sequence per pixel, continued across frames
#define PATTERN_SOBOL 3u

// PCG hash (Jarzynski and Olano, "Hash Functions for GPU Rendering", 2020).
uint pcgHash(uint v) {
    uint state = v * 747796405u + 2891336453u;
    uint word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
    return (word >> 22u) ^ word;
}
float toUnit(uint h) { return float(h >> 8u) * (1.0 / 16777216.0); }  // [0, 1)

uint pixelSeed(uvec2 pixel, uint frame) {
    return pcgHash(pixel.x + pcgHash(pixel.y + pcgHash(frame)));
}

// [region sobol]
// The 2D Sobol sequence is a (0,2)-sequence: every aligned block of 2^k
// consecutive points, the first 2^k included, puts exactly one point in each
// of the 2^k boxes of any 2^a x 2^(k-a) grid. Its first coordinate is the
// radical inverse of i (the bits of i mirrored); the second multiplies the
// bits of i by Pascal's triangle mod 2, whose columns v_k come from v ^= v >> 1.
uint sobolSecond(uint i) {
    uint v = 0x80000000u, y = 0u;
    for (; i != 0u; i >>= 1u, v ^= v >> 1u)
        if ((i & 1u) != 0u) y ^= v;
    return y;
}

// Owen scrambling: flip each bit of x depending on a hash of the bits above
// it, i.e. randomly swap the halves of every interval, nested. It keeps the
// (0,2) property and decorrelates pixels. Laine-Karras hash with the
// constants of Burley, "Practical Hash-based Owen Scrambling", JCGT 2020.
uint owenScramble(uint x, uint seed) {
    // the hash carries from low bits to high: mirror so the top bits lead
    x = bitfieldReverse(x);
    x += seed;
    x ^= x * 0x6c50b47cu;
    x ^= x * 0xb82f1e52u;
    x ^= x * 0xc7afe638u;
    x ^= x * 0x8d22f6e6u;
    return bitfieldReverse(x);
}

// Point `index` of the pixel's own scrambled sequence. Sequences of other
// seeds are other dimensions of one path (a bounce's facet, the pixel's
// jitter) and take the same index: scrambling the index too (bits flipped
// by the bits above them: a shuffle within every aligned block of 2^k, so
// each block stays a net) makes them independent (Burley 2020's padding).
// Unshuffled, their leading bits all follow the index's lowest bit, and a
// pixel's average converges to a wrong value (chapter 15's furnace).
vec2 sobolPoint(uint index, uint seed) {
    index = owenScramble(index, pcgHash(seed + 2u));
    uint x = owenScramble(bitfieldReverse(index), pcgHash(seed));
    uint y = owenScramble(sobolSecond(index), pcgHash(seed + 1u));
    return vec2(toUnit(x), toUnit(y));
}
// [end]

// [region pixel_jitter]
// Chapter 04's antialiasing: point k in [0,1)^2 of the pixel's own sequence
// (a stream of seeds no frame number reaches, so no chapter 11 lobe shares it).
#define JITTER_STREAM 0xA511E9B3u
vec2 pixelJitter(uvec2 pixel, uint k) {
    return sobolPoint(k, pixelSeed(pixel, JITTER_STREAM));
}
// [end]

// [region patterns]
// Point i of n in [0,1)^2. For Sobol, i is the index in the pixel's sequence.
vec2 samplePoint(uint pattern, uint i, uint n, uint seed) {
    if (pattern == PATTERN_SOBOL) return sobolPoint(i, seed);
    vec2 random =
        vec2(toUnit(pcgHash(seed + 2u * i)), toUnit(pcgHash(seed + 2u * i + 1u)));
    if (pattern == PATTERN_STRATIFIED) {
        uint s = uint(sqrt(float(n)) + 0.5);
        if (s * s > n) --s;
        // jitter inside cell i
        if (i < s * s) return (vec2(i % s, i / s) + random) / float(s);
        return random;  // n not a square: the remainder is random
    }
    if (pattern == PATTERN_HAMMERSLEY) {
        vec2 p = vec2((float(i) + 0.5) / float(n),
                      float(bitfieldReverse(i)) * 2.3283064365386963e-10);
        vec2 shift = vec2(toUnit(pcgHash(seed)), toUnit(pcgHash(seed ^ 0x9E3779B9u)));
        return fract(p + shift);  // Cranley-Patterson rotation: a different set per pixel
    }
    return random;
}
// [end]

// An orthonormal basis around the unit vector w (Duff et al., "Building an
// Orthonormal Basis, Revisited", 2017): columns t, b and w itself (chapter
// 14's beams and cones, chapter 15's surface frame).
mat3 basisAround(vec3 w) {
    float s = w.z >= 0.0 ? 1.0 : -1.0;
    float a = -1.0 / (s + w.z), c = w.x * w.y * a;
    return mat3(vec3(1.0 + s * w.x * w.x * a, s * c, -s * w.x),
                vec3(c, s + w.y * w.y * a, -w.y), w);
}

// [region lobe]
// A direction in the cone of half-angle roughness * pi/2 around the unit
// vector r, uniform over the cone's solid angle; u in [0,1)^2.
vec3 lobeDirection(vec3 r, float roughness, vec2 u) {
    float cosMax = cos(roughness * 0.5 * kPi);
    float cosTheta = 1.0 - u.x * (1.0 - cosMax);
    float sinTheta = sqrt(max(0.0, 1.0 - cosTheta * cosTheta));
    float phi = 2.0 * kPi * u.y;
    mat3 frame = basisAround(r);  // t, b, r
    return normalize(sinTheta * cos(phi) * frame[0] + sinTheta * sin(phi) * frame[1] +
                     cosTheta * r);
}
// [end]
#endif
