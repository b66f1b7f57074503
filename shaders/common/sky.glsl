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

vec3 skyRadiance(vec3 d) {
    if (camera.counts.x == 0u) {  // no image: a three-colour gradient
        return d.y >= 0.0 ? mix(camera.skyHorizon.rgb, camera.skyTop.rgb, d.y)
                          : mix(camera.skyHorizon.rgb, camera.skyBottom.rgb, -d.y);
    }
    float u = 0.5 + atan(d.x, -d.z) / (2.0 * kPi);
    float v = acos(clamp(d.y, -1.0, 1.0)) / kPi;
    float x = u * float(camera.counts.x) - 0.5, y = v * float(camera.counts.y) - 0.5;
    int x0 = int(floor(x)), y0 = int(floor(y));
    float fx = x - float(x0), fy = y - float(y0);
    return mix(mix(skyTexel(x0, y0), skyTexel(x0 + 1, y0), fx),
               mix(skyTexel(x0, y0 + 1), skyTexel(x0 + 1, y0 + 1), fx), fy);
}
#endif
