// Chapter 15: the albedo table (host_device.h's ALBEDO_*) read with linear
// interpolation: E(cos_o, roughness, eta), the share of the light one
// microfacet scattering keeps. The includer defines ALBEDO_TABLE(i), entry
// i (rough_surface.glsl: a buffer by device address; the tests: the array).
// Plain GLSL that also compiles as C++.
#ifndef ALBEDO_TABLE_GLSL
#define ALBEDO_TABLE_GLSL

// One slice, bilinear in cos_o and roughness.
float albedoInSlice(uint slice, float cosO, float roughness) {
    float x = clamp(cosO, 0.0f, 1.0f) * float(ALBEDO_COS - 1u);
    float y = clamp(roughness, 0.0f, 1.0f) * float(ALBEDO_ROUGH - 1u);
    uint x0 = min(uint(x), ALBEDO_COS - 2u), y0 = min(uint(y), ALBEDO_ROUGH - 2u);
    float fx = x - float(x0), fy = y - float(y0);
    uint i = (slice * ALBEDO_ROUGH + y0) * ALBEDO_COS + x0;
    float below = mix(ALBEDO_TABLE(i), ALBEDO_TABLE(i + 1u), fx);
    uint j = i + ALBEDO_COS;  // the next roughness
    float above = mix(ALBEDO_TABLE(j), ALBEDO_TABLE(j + 1u), fx);
    return mix(below, above, fy);
}

// [region albedo_lookup]
// A dielectric met from index n1 toward n2: between the two slices of its
// side (entered or left) whose eta enclose n2 / n1.
float dielectricAlbedo(float cosO, float roughness, float n1, float n2) {
    bool leaving = n2 < n1;
    float eta = clamp(leaving ? n1 / n2 : n2 / n1, 1.0f, ALBEDO_ETA_MAX);
    float z = (eta - 1.0f) / (ALBEDO_ETA_MAX - 1.0f) * float(ALBEDO_ETA - 1u);
    uint z0 = min(uint(z), ALBEDO_ETA - 2u);
    uint slice = (leaving ? ALBEDO_ETA : 0u) + z0;
    return mix(albedoInSlice(slice, cosO, roughness),
               albedoInSlice(slice + 1u, cosO, roughness), z - float(z0));
}
float mirrorAlbedo(float cosO, float roughness) {
    return albedoInSlice(ALBEDO_MIRROR_SLICE, cosO, roughness);
}
// [end]
#endif
