// A mesh's texture looked up at a texture coordinate (chapter 12): glTF's
// convention, (0, 0) at the image's top-left corner and (1, 1) at its
// bottom-right, texel centres at half-integers; the sampler's wrap per
// axis, then bilinear weights (or the nearest texel). The texels are read
// one by one (texelFetch: 8-bit values, nothing filters), a colour's
// decoded from sRGB, and the filter is done here in float instead of by a
// Vulkan sampler, so the CPU reference repeats it exactly. Ray tracing has
// no derivatives to choose a mip level from: the closest-hit shader
// estimates the pixel's footprint with a ray cone (mesh.rchit).
#ifndef TEXTURE_GLSL
#define TEXTURE_GLSL
#extension GL_EXT_nonuniform_qualifier : require
#extension GL_EXT_samplerless_texture_functions : require
// [region texture_array]
// One image per texture (rt_textures.h); a material's texture record holds
// its index. Neighbouring rays may hit different materials, so the index is
// marked nonuniformEXT: the driver must not assume one value for them all.
layout(binding = RT_BINDING_TEXTURES) uniform texture2D textures[];
// [end]

// [region wrap]
// A coordinate brought into [0, 1] by the wrap mode; the texel index is
// then wrapped again below, for the neighbours bilinear filtering reads.
float wrapCoordinate(float u, uint mode) {
    if (mode == TEXTURE_WRAP_CLAMP) return clamp(u, 0.0, 1.0);
    // 0..1..0 with period 2
    if (mode == TEXTURE_WRAP_MIRROR) return 1.0 - abs(mod(u, 2.0) - 1.0);
    return fract(u);
}
int wrapTexel(int i, int n, uint mode) {
    if (mode == TEXTURE_WRAP_REPEAT) return (i % n + n) % n;
    // clamped, or mirrored: the edge texel repeats at the turn
    return clamp(i, 0, n - 1);
}
// [end]

// Texel (x, y) of mip level `level`, w x h texels: decoded to linear light.
vec4 texel(uvec4 t, int level, int w, int h, int x, int y) {
    x = wrapTexel(x, w, t.w & 3u);
    y = wrapTexel(y, h, (t.w >> TEXTURE_V_SHIFT) & 3u);
    vec4 v = texelFetch(textures[nonuniformEXT(t.x)], ivec2(x, y), level);
    if ((t.w & TEXTURE_SRGB) != 0u) {  // the sRGB curve (IEC 61966-2-1), exactly
        bvec3 low = lessThanEqual(v.rgb, vec3(0.04045));
        v.rgb = mix(pow((v.rgb + 0.055) / 1.055, vec3(2.4)), v.rgb / 12.92, low);
    }
    return v;
}

// One level, bilinear (or the nearest texel). Its size is level 0's halved
// `level` times, at least 1.
vec4 sampleLevel(uvec4 t, vec2 uv, int level, bool nearest) {
    int w = max(int(t.y) >> level, 1), h = max(int(t.z) >> level, 1);
    float x = wrapCoordinate(uv.x, t.w & 3u) * float(w);
    float y = wrapCoordinate(uv.y, (t.w >> TEXTURE_V_SHIFT) & 3u) * float(h);
    if (nearest) return texel(t, level, w, h, int(floor(x)), int(floor(y)));
    x -= 0.5;
    y -= 0.5;  // between the four nearest texel centres
    int x0 = int(floor(x)), y0 = int(floor(y));
    float fx = x - float(x0), fy = y - float(y0);
    return mix(mix(texel(t, level, w, h, x0, y0), texel(t, level, w, h, x0 + 1, y0), fx),
               mix(texel(t, level, w, h, x0, y0 + 1),
                   texel(t, level, w, h, x0 + 1, y0 + 1), fx),
               fy);
}

// The level of detail of texture t for a footprint of 2^footprint in
// texture coordinates (mesh.rchit's coneLod): in texels, log2 of w h's root.
float texelLod(uvec4 t, float footprint) {
    return footprint + 0.5 * log2(float(t.y) * float(t.z));
}

// [region sample]
// Linear colour in rgb, and alpha (glTF: linear too) in a, at level of
// detail `lod` (log2 of texels a pixel's footprint spans: mesh.rchit's ray
// cone). lod <= 0 magnifies: level 0 with the magnification filter; above,
// the minification filter within levels and the mipmap mode between them
// (glTF's minFilter; the Vulkan specification's "Texel Filtering").
vec4 sampleTexture(uvec4 t, vec2 uv, float lod) {
    if (!(lod > 0.0)) return sampleLevel(t, uv, 0, (t.w & TEXTURE_NEAREST) != 0u);
    bool nearest = (t.w & TEXTURE_MIN_NEAREST) != 0u;
    uint mipmap = (t.w >> TEXTURE_MIPMAP_SHIFT) & 3u;
    float last = float(((t.w >> TEXTURE_LEVELS_SHIFT) & 0xFFu) - 1u);
    if (mipmap == 0u || last == 0.0) return sampleLevel(t, uv, 0, nearest);
    lod = min(lod, last);
    if (mipmap == TEXTURE_MIPMAP_NEAREST)
        return sampleLevel(t, uv, int(floor(lod + 0.5)), nearest);
    int below = int(floor(lod));  // trilinear: the two levels around lod
    vec4 a = sampleLevel(t, uv, below, nearest);
    return below == int(last) ? a
                              : mix(a, sampleLevel(t, uv, below + 1, nearest),
                                    lod - float(below));
}
// [end]
#endif
