// Fresnel reflectance of a dielectric interface (thesis 4.1.1), for light
// going from index n1 into index n2, with cosI = cos(angle of incidence) >= 0.
// Plain GLSL that also compiles as C++ (tests/test_fresnel.cpp).
#ifndef FRESNEL_GLSL
#define FRESNEL_GLSL

#define FRESNEL_SCHLICK 0u      // Schlick with the material's f0 (the thesis: 0.08)
#define FRESNEL_SCHLICK_IOR 1u  // Schlick with f0 = ((n - 1) / (n + 1))^2
#define FRESNEL_EXACT 2u        // the unpolarized Fresnel equations

// [region fresnel]
float f0FromIor(float n1, float n2) {
    float r = (n1 - n2) / (n1 + n2);
    return r * r;  // 0.042 for glass (1.517) in air
}

// Schlick: F = F0 + (1 - F0)(1 - cos)^5.
float schlick(float f0, float cosine) {
    float m = 1.0f - cosine;
    return f0 + (1.0f - f0) * (m * m) * (m * m) * m;
}

// sin^2 of the refracted angle (Snell: n1 sin(i) = n2 sin(t)); > 1 means
// total internal reflection.
float sin2Transmitted(float cosI, float n1, float n2) {
    float eta = n1 / n2;
    return eta * eta * max(0.0f, 1.0f - cosI * cosI);
}

// The exact reflectance for unpolarized light: the mean of the s and p
// polarizations' reflectances.
float fresnelExact(float cosI, float n1, float n2) {
    float s2 = sin2Transmitted(cosI, n1, n2);
    if (s2 >= 1.0f) return 1.0f;  // total internal reflection
    float cosT = sqrt(1.0f - s2);
    float rs = (n1 * cosI - n2 * cosT) / (n1 * cosI + n2 * cosT);
    float rp = (n2 * cosI - n1 * cosT) / (n2 * cosI + n1 * cosT);
    return 0.5f * (rs * rs + rp * rp);
}

// The reflectance a mode gives. Leaving a denser medium, Schlick must use the
// transmitted angle's cosine (else it misses total internal reflection).
float fresnel(uint mode, float f0, float cosI, float n1, float n2) {
    if (mode == FRESNEL_EXACT) return fresnelExact(cosI, n1, n2);
    float s2 = sin2Transmitted(cosI, n1, n2);
    if (s2 >= 1.0f) return 1.0f;
    float cosine = n1 > n2 ? sqrt(1.0f - s2) : cosI;
    return schlick(mode == FRESNEL_SCHLICK ? f0 : f0FromIor(n1, n2), cosine);
}
// [end]
#endif
