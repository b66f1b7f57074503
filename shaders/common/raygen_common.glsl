// What every ray generation shader from chapter 05 on shares: its outputs
// (chapter 04's running mean included), its payload, the primary trace (as
// chapter 04 writes it out), and the normal on the side the ray came from.
#ifndef RAYGEN_COMMON_GLSL
#define RAYGEN_COMMON_GLSL
layout(binding = RT_BINDING_TARGET, rgba32f) uniform image2D target;
layout(binding = RT_BINDING_RAY_COUNT, std430) writeonly buffer RayCount {
    uint rayCount[];
};
layout(location = 0) rayPayloadEXT HitPayload payload;

// [region cone]
// Chapter 12's ray cones (mesh.rchit's coneLod): the angle one pixel spans
// at the centre of the image, atan(2 tan(fov_y / 2) / height) (projInverse
// holds tan(fov_y / 2)).
float pixelSpread() {
    return atan(2.0 * abs(camera.projInverse[1][1]) / float(imageSize(target).y));
}
// [end]

// The closest hit along the ray into `payload` (a miss leaves the sky's
// radiance). The ray leaves with its cone in the payload's radiance, which
// the hit overwrites: how far from the eye its path began (`coneStart`: 0
// for a camera ray, then the camera ray's hit distance) and the spread.
void traceClosest(vec3 origin, float tMin, vec3 direction, float tMax,
                  float coneStart) {
    if (kRayCones) payload.radiance.xy = vec2(coneStart, pixelSpread());
    traceRayEXT(tlas, kRayFlags, 0xFF, RAY_TYPE_PRIMARY, 0, MISS_SKY, origin, tMin,
                direction, tMax, 0);
}

void traceClosest(vec3 origin, float tMin, vec3 direction, float tMax) {
    traceClosest(origin, tMin, direction, tMax, 0.0);
}

void traceClosest(vec3 origin, float tMin, vec3 direction) {
    traceClosest(origin, tMin, direction, kInfinity);
}

// The geometric normal turned toward the ray's origin: opaque surfaces are
// lit on the side they are seen from.
vec3 facingNormal(vec3 normal, vec3 direction) {
    return dot(normal, direction) < 0.0 ? normal : -normal;
}

// [region shading_normal]
// Chapter 12: the shading normal turned with the geometric one. Where it
// faces away from the ray (an interpolated normal near a silhouette), the
// flat triangle's own normal shades instead: a cosine below zero has no
// meaning for Fresnel or for a highlight.
vec3 facingShading(vec3 shading, vec3 normal, vec3 direction) {
    vec3 ns = dot(normal, direction) < 0.0 ? shading : -shading;
    return dot(ns, direction) < 0.0 ? ns : facingNormal(normal, direction);
}
// [end]
// The payload's hit: only meshes write a shading normal of their own, and
// only in a scene that has them (kMeshes); elsewhere it is the surface's.
vec3 hitFacingShading(vec3 direction) {
    return kMeshes ? facingShading(payload.shading, payload.normal, direction)
                   : facingNormal(payload.normal, direction);
}

// [region metal_roughness]
// glTF's metal-roughness model at one hit, as shared/scene/rules.cpp's
// applyMetalRoughness sets it up for a whole material (chapter 12).
void applyMetalRoughness(inout GpuMaterial m, vec3 baseColor, float metallic,
                         float roughness) {
    float transmission = m.params.z;
    m.kd.rgb = baseColor * ((1.0 - metallic) * (1.0 - transmission));
    m.ka.rgb = m.kd.rgb;
    float alpha = max(roughness * roughness, 1e-3);
    m.params.x = min(1e6, max(1.0, 2.0 / (alpha * alpha) - 2.0));  // shininess
    m.ks.rgb = vec3(0.04 * (1.0 - roughness));
    m.params.y = metallic * (1.0 - transmission);                   // reflectivity
    m.extra.y = transmission > 0.0 ? roughness : roughness * metallic;  // rough lobe
}
// [end]

// [region hit_material]
// The material of what the last trace hit. On a mesh, mesh.rchit brought
// back its textures' values in the payload's radiance (payload.glsl): the
// base colour tints the ambient and diffuse colours; a metal-roughness
// texture varies the whole material (chapter 12).
GpuMaterial hitMaterial() {
    GpuObject o = objects[payload.object];
    GpuMaterial m = materials[o.material];
    if (o.shape == SHAPE_MESH) {
        HitTextures h = unpackHitTextures(payload.radiance);
        if ((m.flags & MATERIAL_METAL_ROUGH) != 0u) {
            applyMetalRoughness(m, m.baseColor.rgb * h.baseColor,
                                m.baseColor.w * h.metalness, m.factors.x * h.roughness);
        } else {
            m.ka.rgb *= h.baseColor;
            m.kd.rgb *= h.baseColor;
        }
    }
    return m;
}
// [end]

// [region write_pixel]
// Chapter 04's running mean (--antialias, and chapter 11's rough samples),
// of the radiance: the target holds it exposed.
void writePixelAt(uvec2 pixel, vec3 color, uint rays) {
    if (kAverages && push.accumulated > 0u) {  // kAverages: rt_bindings.glsl
        vec3 mean = imageLoad(target, ivec2(pixel)).rgb / push.exposure;
        color = mix(mean, color, 1.0 / float(push.accumulated + 1u));
    }
    // --exposure: 1 unless asked
    imageStore(target, ivec2(pixel), vec4(color * push.exposure, 1.0));
    rayCount[pixel.y * uint(imageSize(target).x) + pixel.x] = rays;
}
// [end]

void writePixel(vec3 color, uint rays) { writePixelAt(gl_LaunchIDEXT.xy, color, rays); }
#endif
