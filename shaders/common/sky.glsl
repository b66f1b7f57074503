// The sky, looked up by direction (the miss shader, thesis 2.2.3):
// equirectangular, u = 0.5 + atan(x, -z) / 2pi, v = acos(y) / pi, bilinear
// between texel centres, wrapping around in u. Filtering is done here in
// float rather than by a sampler, so the CPU reference repeats it exactly.
#ifndef SKY_GLSL
#define SKY_GLSL
vec3 skyTexel(int x, int y) {
    int w = int(camera.counts.x), h = int(camera.counts.y);
    x = (x % w + w) % w;
    y = clamp(y, 0, h - 1);
    return skyTexels[y * w + x].rgb;
}

// atan2 to about 1e-7 rad (Cephes' atanf: range reduction by tan(pi/8) and
// tan(3pi/8), then a degree-9 odd polynomial). GLSL's own atan may be far
// less exact (Vulkan allows it), and at a landmark's edge in the sky an
// angle error of 5e-5 rad already changes the colour by 1/255.
float preciseAtan2(float y, float x) {
    float ax = abs(x), ay = abs(y);
    float t = min(ax, ay) / max(max(ax, ay), 1e-30);  // in [0, 1]
    float offset = 0.0;
    if (t > 0.41421356) {  // tan(pi/8)
        t = (t - 1.0) / (t + 1.0);
        offset = 0.25 * kPi;
    }
    float z = t * t;
    float r = (((8.05374449538e-2 * z - 1.38776856032e-1) * z + 1.99777106478e-1) * z -
               3.33329491539e-1) *
                  z * t +
              t;
    r += offset;
    if (ay > ax) r = 0.5 * kPi - r;
    if (x < 0.0) r = kPi - r;
    return y < 0.0 ? -r : r;
}

vec3 skyRadiance(vec3 d) {
    if (camera.counts.x == 0u) {  // no image: a three-colour gradient
        return d.y >= 0.0 ? mix(camera.skyHorizon.rgb, camera.skyTop.rgb, d.y)
                          : mix(camera.skyHorizon.rgb, camera.skyBottom.rgb, -d.y);
    }
    float u = 0.5 + preciseAtan2(d.x, -d.z) / (2.0 * kPi);
    // = acos(y) for a unit d, exact near the poles too
    float v = preciseAtan2(length(d.xz), d.y) / kPi;
    float x = u * float(camera.counts.x) - 0.5, y = v * float(camera.counts.y) - 0.5;
    int x0 = int(floor(x)), y0 = int(floor(y));
    float fx = x - float(x0), fy = y - float(y0);
    return mix(mix(skyTexel(x0, y0), skyTexel(x0 + 1, y0), fx),
               mix(skyTexel(x0, y0 + 1), skyTexel(x0 + 1, y0 + 1), fx), fy);
}
#endif
