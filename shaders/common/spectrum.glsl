// Chapter 13: dispersion. A glass's index depends on the wavelength, so
// white light entering a prism leaves as a fan of colours. A path that
// meets such a surface carries one wavelength from there on: its light is
// weighted by what the eye's three channels see of that wavelength (the
// CIE 1931 matching functions, to linear sRGB), and the mean over many
// paths, frame after frame, is the colour.
#ifndef SPECTRUM_GLSL
#define SPECTRUM_GLSL
#include "sampling.glsl"

// [region index]
// n^2 = 1 + sum B_i L^2 / (L^2 - C_i), L in micrometres (host_device.h's glasses).
float sellmeier(float nm, float B1, float B2, float B3, float B4, float C1, float C2,
                float C3, float C4) {
    float l2 = nm * nm * 1e-6;
    return sqrt(1.0 + B1 * l2 / (l2 - C1) + B2 * l2 / (l2 - C2) + B3 * l2 / (l2 - C3) +
                B4 * l2 / (l2 - C4));
}

// A material's index at `nm`: its glass, or glTF's Abbe-number line about
// n_d (KHR_materials_dispersion), or its one index.
float indexAt(GpuMaterial m, float nm) {
    uint glass = uint(m.extra.w);
    if (glass == GLASS_BK7) return sellmeier(nm, SELLMEIER_BK7);
    if (glass == GLASS_FUSED_SILICA) return sellmeier(nm, SELLMEIER_FUSED_SILICA);
    if (glass == GLASS_WATER) return sellmeier(nm, SELLMEIER_WATER);
    if (glass == GLASS_DIAMOND) return sellmeier(nm, SELLMEIER_DIAMOND);
    float nd = m.params.w, inverseAbbe = m.extra.z;  // glTF's dispersion / 20
    return max(nd + (nd - 1.0) * inverseAbbe * (523655.0 / (nm * nm) - 1.5168), 1.0);
}
// [end]

// [region weight]
// Wyman, Sloan and Shirley 2013: the CIE 1931 matching functions as sums of
// Gaussians with a different width either side of their peak.
float lobe(float nm, float peak, float below, float above) {
    float t = (nm - peak) / (nm < peak ? below : above);
    return exp(-0.5 * t * t);
}

vec3 cieXyz(float nm) {
    return vec3(
        1.056 * lobe(nm, 599.8, 37.9, 31.0) + 0.362 * lobe(nm, 442.0, 16.0, 26.7) -
            0.065 * lobe(nm, 501.1, 20.4, 26.2),
        0.821 * lobe(nm, 568.8, 46.9, 40.5) + 0.286 * lobe(nm, 530.9, 16.3, 31.1),
        1.217 * lobe(nm, 437.0, 11.8, 36.0) + 0.681 * lobe(nm, 459.0, 26.0, 13.8));
}

// What one wavelength, drawn uniformly from the visible range, is worth in
// each linear sRGB channel: the matching functions turned to sRGB (D65's
// matrix), over their mean across the range. Averaged over wavelengths each
// channel is 1, so white light through a glass that bends every wavelength
// alike stays white; a channel may be negative for one wavelength.
vec3 spectralWeight(float nm) {
    vec3 xyz = cieXyz(nm);
    vec3 rgb = vec3(dot(vec3(3.2404542, -1.5371385, -0.4985314), xyz),
                    dot(vec3(-0.9692660, 1.8760108, 0.0415560), xyz),
                    dot(vec3(0.0556434, -0.2040259, 1.0572252), xyz));
    return rgb * vec3(SPECTRUM_WEIGHT_SCALE);
}
// [end]

// [region wavelength]
// The base-2 radical inverse (van der Corput): frame k of an accumulation
// fills the gaps the frames before it left, so after 2^m frames a pixel has
// one wavelength in each of 2^m equal bands. Each pixel shifts the
// sequence by its own offset, so neighbours differ (Cranley-Patterson).
float pathWavelength(uint accumulated, uint seed) {
    float u = fract(toUnit(bitfieldReverse(accumulated)) + toUnit(seed));
    return mix(SPECTRUM_MIN_NM, SPECTRUM_MAX_NM, u);
}
// [end]
#endif
