// Chapter 13: which medium a ray travels in. Chapter 10 takes the outside
// of every glass to be air; here each branch of a ray tree carries the
// media it is inside, a stack of material indices (Branch::media, 8 bits
// each, the most recently entered in the low byte, 0: an empty place).
// Where media overlap (water poured against a glass's wall), the one of
// highest priority fills the space (Schmidt and Budge 2002, "Simple nested
// dielectrics in ray traced images"), so each surface a ray meets is judged
// by the two media that really meet there.
#ifndef MEDIA_GLSL
#define MEDIA_GLSL
#include "spectrum.glsl"

// media a ray can be inside at once; entering a fifth forgets the first
#define MEDIA_DEPTH 4u

// [region stack]
uint mediumEntry(uint media, uint i) { return (media >> (8u * i)) & 0xFFu; }

// The medium that fills the ray's place: the entry of highest priority,
// of equal ones the last entered. Material index + 1; 0: air.
uint currentMedium(uint media) {
    uint best = 0u;
    float bestPriority = -1.0;
    for (uint i = 0u; i < MEDIA_DEPTH; ++i) {
        uint id = mediumEntry(media, i);
        if (id == 0u) break;
        float priority = materials[id - 1u].medium.w;
        if (priority > bestPriority) best = id, bestPriority = priority;
    }
    return best;
}

uint enterMedium(uint media, uint material) { return (media << 8u) | (material + 1u); }

// The stack without its last entry of `material`; unchanged if the ray was
// not inside it (a camera placed inside without camera.medium, an open mesh).
uint leaveMedium(uint media, uint material) {
    for (uint i = 0u; i < MEDIA_DEPTH; ++i) {
        if (mediumEntry(media, i) != material + 1u) continue;
        uint below = media & ((1u << (8u * i)) - 1u);               // entered after it
        // entered before it
        uint above = i + 1u < MEDIA_DEPTH ? media >> (8u * (i + 1u)) : 0u;
        return below | (above << (8u * i));
    }
    return media;
}
// [end]

float mediumIor(uint id) { return id == 0u ? 1.0 : materials[id - 1u].params.w; }
vec3 mediumAbsorption(uint id) {
    return id == 0u ? vec3(0.0) : materials[id - 1u].medium.rgb;
}
vec2 mediumDispersion(uint id) {
    return id == 0u ? vec2(0.0) : materials[id - 1u].extra.zw;
}
float mediumIorAt(uint id, float nm) {
    return id == 0u ? 1.0 : indexAt(materials[id - 1u], nm);
}

// [region boundary]
// What a ray inside `media` meets where it enters or leaves `material`: the
// indices on the two sides, and the media beyond. When the medium does not
// change (a lower-priority medium's surface inside a higher one, glass
// inside the same glass) there is no surface there at all: real = false.
struct Boundary {
    bool real;
    uint from, to;  // the two media (material index + 1, 0: air)
    float n1, n2;   // their indices (at 587.6 nm where they disperse)
    uint beyond;    // the media of a ray that crosses
};

Boundary boundaryAt(uint media, uint material, bool entering) {
    Boundary b;
    b.from = currentMedium(media);
    b.beyond = entering ? enterMedium(media, material) : leaveMedium(media, material);
    b.to = currentMedium(b.beyond);
    // leaving what it never entered: chapter 10's view
    if (!entering && b.beyond == media) b.from = material + 1u;
    b.n1 = mediumIor(b.from);
    b.n2 = mediumIor(b.to);
    b.real = b.n1 != b.n2 || mediumAbsorption(b.from) != mediumAbsorption(b.to)
          || mediumDispersion(b.from) != mediumDispersion(b.to);
    return b;
}
// [end]

// [region beer_lambert]
// Beer-Lambert: along a distance t inside the current medium, light falls
// by exp(-sigma t). A ray that leaves the scene (t < 0) inside an absorbing
// medium goes on forever: nothing of it arrives.
vec3 transmittance(uint media, float t) {
    vec3 sigma = mediumAbsorption(currentMedium(media));
    if (t < 0.0) return vec3(equal(sigma, vec3(0.0)));
    return exp(-sigma * t);
}
// [end]
#endif
