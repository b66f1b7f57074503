// The one header that C++ and GLSL both include: descriptor bindings, push
// constants and the structs the GPU reads. Each struct follows std430 rules
// (vec4-aligned members first), and C++ static_asserts its size, so a field
// added on one side only fails the build instead of shifting every read.
#ifndef RG_HOST_DEVICE_H
#define RG_HOST_DEVICE_H

#ifdef __cplusplus
#include <cstdint>
#include <glm/glm.hpp>
namespace rg::gpu {
using uint = uint32_t;
using vec2 = glm::vec2;
using vec3 = glm::vec3;
using vec4 = glm::vec4;
using uvec2 = glm::uvec2;
using uvec4 = glm::uvec4;
using mat4 = glm::mat4;
#define RG_SIZE(T, bytes) \
    static_assert(sizeof(T) == (bytes), #T ": size differs from its GLSL layout")
#define RG_INLINE inline
#else
#define RG_SIZE(T, bytes)
#define RG_INLINE
#endif

// ---- Chapters 01-02: a compute shader writes a test pattern ----------------
#define PATTERN_BINDING_TARGET 0  // storage image, rgba32f, linear values
#define PATTERN_GROUP_SIZE 8      // 8x8 invocations per workgroup
#define PATTERN_SCROLL 240.0      // chapter 02: checker pixels scrolled per second
#define PATTERN_FPS 60.0          // chapter 02: animation time = frame / PATTERN_FPS

struct PatternPush {
    uint width;
    uint height;
    float time;     // seconds of animation time (chapter 02), 0 in chapter 01
    uint checker;   // checker square size in pixels
};
RG_SIZE(PatternPush, 16);

// ---- Chapter 03: a top view of the TLAS instances --------------------------
#define FOOTPRINT_BINDING_TARGET 0     // storage image
// the VkAccelerationStructureInstanceKHR array the TLAS is built from
#define FOOTPRINT_BINDING_INSTANCES 1

// VkAccelerationStructureInstanceKHR as GLSL sees it: a 3x4 row-major
// transform, then customIndex|mask, sbtOffset|flags, the BLAS address.
struct InstanceRecord {
    vec4 row0;
    vec4 row1;
    vec4 row2;
    uint customIndexAndMask;
    uint sbtOffsetAndFlags;
    uint blasAddressLow;
    uint blasAddressHigh;
};
RG_SIZE(InstanceRecord, 64);

struct FootprintPush {
    vec4 bounds;  // world x and z of the image's top-left corner, then the size covered
    uint width;
    uint height;
    uint instanceCount;
    uint pad;
};
RG_SIZE(FootprintPush, 32);

// Instance i's colour in the top view: 8 distinct colours.
RG_INLINE vec3 instanceColor(uint i) {
    uint k = i % 8u;
    return vec3(float(k & 1u), float((k >> 1u) & 1u), float((k >> 2u) & 1u)) * 0.6f +
           vec3(0.25f);
}

// ---- Chapters 04-11: the ray tracing pipeline ------------------------------
#define RT_BINDING_TLAS 0       // the scene's top-level acceleration structure
#define RT_BINDING_TARGET 1     // storage image, rgba32f, linear radiance
#define RT_BINDING_CAMERA 2     // uniform RtCamera
// GpuObject[], indexed by gl_InstanceCustomIndexEXT + gl_PrimitiveID
#define RT_BINDING_OBJECTS 3
#define RT_BINDING_MATERIALS 4  // GpuMaterial[]
#define RT_BINDING_LIGHTS 5     // GpuLight[]
#define RT_BINDING_SKY 6        // vec4[] linear sky texels, row-major, top row first
#define RT_BINDING_RAY_COUNT 7  // uint[] rays traced per pixel in the last frame
// GpuMesh[]: where each mesh's buffers are (chapter 12, --sphere-mesh)
#define RT_BINDING_MESHES 8
// texture2D[]: the meshes' textures, one image each (chapter 12)
#define RT_BINDING_TEXTURES 9

#define SHAPE_SPHERE 0u
#define SHAPE_QUAD 1u
#define SHAPE_MESH 2u

// Hit groups in the SBT: one per shape and ray type (see shared/raytracing/sbt.h).
#define HIT_GROUP_QUAD 0u
#define HIT_GROUP_SPHERE 1u
// triangle meshes (chapter 12) and the tessellated sphere (--sphere-mesh)
#define HIT_GROUP_MESH 2u
#define RAY_TYPE_PRIMARY 0u  // sbtRecordOffset of camera and bounce rays
// sbtRecordOffset of shadow rays (chapter 06 on): after the 3 primary groups
#define RAY_TYPE_SHADOW 3u
#define MISS_SKY 0u
#define MISS_SHADOW 1u
#define MISS_TRANSMIT 2u  // chapter 14's --caustics transmit: its shadow rays' miss

struct RtCamera {
    mat4 viewInverse;  // camera -> world
    mat4 projInverse;  // clip -> camera (Vulkan clip space: y points down)
    vec4 skyTop;       // gradient sky when there is no sky image
    vec4 skyHorizon;
    vec4 skyBottom;
    vec4 ambient;      // I_a (chapter 05)
    uvec4 counts;      // sky width, sky height (0: gradient), light count, object count
    // camera rays' tMin (Scene::eyeTmin, 0 unless the eye lies on a surface)
    float eyeTmin;
    // the medium the eye is in (chapter 13): its material index + 1, 0 for air
    uint eyeMedium;
    uint unused0, unused1;  // the struct's size stays a multiple of 16 bytes
};
RG_SIZE(RtCamera, 224);

struct GpuObject {
    vec4 sphere;    // centre, radius in its instance's object space: (0,0,0,1)
                    // for an instance of the unit sphere, the real one in a sphere group
    uint shape;     // SHAPE_*
    uint material;  // index into materials
    // world space: the ball of this radius about the centre holds the shape (0: a quad, a
    // mesh)
    float radius;
    uint mesh;      // SHAPE_MESH: index into the mesh table (chapter 12)
};
RG_SIZE(GpuObject, 32);

// [region gpu_mesh]
// Chapter 12: a mesh's buffers by device address (low, high 32 bits), read
// in the closest-hit shader through GL_EXT_buffer_reference: no descriptor
// per mesh, however many meshes a scene has.
struct GpuMesh {
    uvec2 vertices;  // vec3 positions, tightly packed (the BLAS was built from them)
    uvec2 normals;   // vec3 per vertex; (0, 0): none, the faces are flat
    uvec2 indices;   // uint, three per triangle
    // vec2 per vertex, glTF's (0, 0) at the image's top-left; (0, 0): none
    uvec2 texcoords;
};
RG_SIZE(GpuMesh, 32);
// [end]

// [region material]
struct GpuMaterial {
    vec4 ka;
    vec4 kd;
    vec4 ks;
    vec4 params;   // shininess, reflectivity, transmission, ior
    // f0, roughness; chapter 13's dispersion: 1 / Abbe number (0: none), GLASS_*
    vec4 extra;
    uvec4 texture; // chapter 12's base colour texture: its index in textures[],
                   // width, height (0: none), TEXTURE_* flags
    // chapter 13: absorption coefficient per unit length (rgb, Beer-Lambert), priority
    vec4 medium;
    uint flags;         // MATERIAL_* bits
    // chapter 12, glTF's alphaMode MASK: hits whose alpha is below this do
    // not count (0: every hit counts); alpha: baseColorFactor's, times the texture's
    float alphaCutoff;
    float alpha;
    uint unused;        // the struct's size stays a multiple of 16 bytes
    // chapter 12, glTF's metal-roughness model where a texture varies it per
    // hit (MATERIAL_METAL_ROUGH): baseColorFactor (rgb), metallicFactor
    vec4 baseColor;
    // roughnessFactor, the normal texture's scale, unused, unused
    vec4 factors;
    uvec4 metalRoughTexture;  // as `texture`: roughness in G, metalness in B (linear)
    uvec4 normalTexture;      // as `texture`: tangent-space normals (linear)
};
RG_SIZE(GpuMaterial, 192);
#define MATERIAL_THIN 1u  // thin-walled transmission: crossed unbent (Material::thin)
// chapter 12: a metal-roughness texture; hitMaterial redoes the glTF
// mapping (Material::metalRough) at each hit
#define MATERIAL_METAL_ROUGH 2u
// [end]

// GpuMaterial::texture.w: how each axis wraps (glTF's samplers), and the filter.
#define TEXTURE_WRAP_REPEAT 0u
#define TEXTURE_WRAP_CLAMP 1u
#define TEXTURE_WRAP_MIRROR 2u
#define TEXTURE_V_SHIFT 2u    // bits 0-1: u's wrap, bits 2-3: v's
#define TEXTURE_NEAREST 16u   // magnification NEAREST; else bilinear
#define TEXTURE_SRGB 32u      // a colour: its 8-bit rgb is sRGB-encoded
#define TEXTURE_MIN_NEAREST 64u  // minification NEAREST within a level; else bilinear
#define TEXTURE_MIPMAP_SHIFT 7u  // bits 7-8: between levels (TextureMipmap):
#define TEXTURE_MIPMAP_NEAREST 1u  //   the nearest level,
#define TEXTURE_MIPMAP_LINEAR 2u   //   a blend of two (trilinear); 0: level 0 only
#define TEXTURE_LEVELS_SHIFT 16u   // bits 16-23: its mip levels

// [region glasses]
// Chapter 13: the glasses a scene names for its dispersion (GpuMaterial::
// extra.w), each by Sellmeier's equation n^2 = 1 + sum B_i L^2 / (L^2 - C_i),
// L in micrometres, C_i in square micrometres: B1..B4, C1..C4.
#define GLASS_NONE 0u          // the Abbe number in extra.z, or no dispersion
#define GLASS_BK7 1u           // SCHOTT N-BK7 (its datasheet)
#define GLASS_FUSED_SILICA 2u  // Malitson 1965, 20 C
#define GLASS_WATER 3u         // Daimon and Masumura 2007, 20 C
#define GLASS_DIAMOND 4u       // Peter 1923
#define SELLMEIER_BK7 1.03961212, 0.231792344, 1.01046945, 0.0, \
                      0.00600069867, 0.0200179144, 103.560653, 1.0
#define SELLMEIER_FUSED_SILICA                                                          \
    0.6961663, 0.4079426, 0.8974794, 0.0, 0.0684043 * 0.0684043, 0.1162414 * 0.1162414, \
        9.896161 * 9.896161, 1.0
#define SELLMEIER_WATER 0.5684027565, 0.1726177391, 0.02086189578, 0.1130748688, \
                      0.005101829712, 0.01821153936, 0.02620722293, 10.69792721
#define SELLMEIER_DIAMOND \
    0.3306, 4.3356, 0.0, 0.0, 0.1750 * 0.1750, 0.1060 * 0.1060, 1.0, 1.0
// [end]

// Chapter 13's wavelengths: a path that meets a dispersive surface carries
// one wavelength, drawn uniformly from this range (nm).
#define SPECTRUM_MIN_NM 380.0
#define SPECTRUM_MAX_NM 780.0
// (MAX - MIN) / the integral of each linear sRGB channel of the CIE 1931
// matching functions over the range (Wyman, Sloan and Shirley's fit): one
// wavelength's weight averages to 1 in every channel. test_13_real_glass
// integrates the fit again and checks these.
#define SPECTRUM_WEIGHT_SCALE 3.1162108, 3.9394087, 4.1209583

struct GpuLight {
    vec4 position;   // xyz; w: LIGHT_* (a directional light: where its light travels)
    // the thesis's I_i; chapter 14: W/sr, or a sun's irradiance (W/m^2) and in w
    // its angular radius (radians)
    vec4 intensity;
};
RG_SIZE(GpuLight, 32);
#define LIGHT_POINT 1.0        // position.w: a point light
#define LIGHT_DIRECTIONAL 2.0  // chapter 14: a sun, position.xyz its unit direction

// Chapter 10's launches: one traces every pixel's whole ray tree; or the
// first traces each pixel's camera ray and queues the trees that go on, and
// a second launch, as wide as the queue, traces those (docs/10_refraction.md).
// Each is its own pipeline: the ray generation shader's specialization constant.
#define LAUNCH_ONE 0u
#define LAUNCH_FIRST 1u
#define LAUNCH_QUEUED 2u

// Per frame, as push constants: nothing a frame in flight still reads changes.
struct RtPush {
    uint frame;
    uint maxDepth;       // bounce limit (chapter 08 on)
    uint samplesPerHit;  // rough reflection rays per hit (chapter 11)
    uint pattern;        // sample pattern (chapter 11)
    // 0 Schlick with the material's f0, 1 Schlick with f0 from the IOR, 2 exact (chapter
    // 09)
    uint fresnelMode;
    // frames already averaged into the target (chapter 04's antialiasing, 11's rough
    // reflections)
    uint accumulated;
    // > 0: chapter 06's fixed-epsilon experiment instead of the robust offset
    float epsilon;
    // chapter 13: > 0, every path at this wavelength (nm); 0: one drawn per path
    float wavelength;
    // the tree queue's device address, low and high 32 bits (chapter 10)
    uvec2 treeQueue;
    // 2^EV, what the written radiance is scaled by (--exposure; chapter 05 on)
    float exposure;
    // 1: each frame's camera rays pass a new point of the pixel (--antialias, chapter 04)
    uint antialias;
    // chapter 14: the photon map's PhotonMapHeader by device address (0: none)
    uvec2 photonMap;
    float photonRadius;  // this frame's gathering radius (world units)
    uint photonsEmitted;  // photons traced from the lights this frame
    uint caustics;        // chapter 14's --caustics: CAUSTICS_*
    uint photonSeed;      // chapter 14's --photon-seed: another set of photons
    uint facetSampling;   // chapter 15's --sampling: FACETS_VISIBLE or FACETS_CONE
    // chapter 15's --multiple-scattering: 1 compensates the light single
    // scattering loses, with the albedo table at albedoTable (device address)
    uint multipleScattering;
    uvec2 albedoTable;
    // chapter 14's --gather-cap: a gather reads at most this many photons of a
    // cell, a random run of them weighted up (0: all; gather.glsl)
    uint gatherCap;
    // chapter 14's --gather-defer: a cell holding more photons than this is
    // gathered by a compute pass after the camera rays (gather.glsl's
    // gather_defer; 0: every cell where it is met)
    uint gatherDefer;
    // chapter 15's --roulette: past maxDepth a branch goes on as one path,
    // ended by Russian roulette, up to this many bounces (<= maxDepth: cut)
    uint maxPathDepth;
    // chapter 15's --rough-branches one: 1, past the camera ray's hit a rough
    // surface sends one branch on, chosen by the shares (ray_tree.glsl)
    uint oneRoughBranch;
};
RG_SIZE(RtPush, 104);
#define ROULETTE_MAX_DEPTH 4095u  // --roulette on: a path's last bounce (page 15)
#define CAUSTICS_OFF 0u       // glass stops shadow rays: black shadows
#define CAUSTICS_PHOTONS 1u   // photons carry the light that passes glass
#define CAUSTICS_TRANSMIT 2u  // shadow rays pass glass unbent (transmit.glsl)
#define FACETS_VISIBLE 0u  // a rough hit draws a visible normal (microfacet.glsl)
#define FACETS_CONE 1u     // ... or a direction in chapter 11's cone (the comparison)

// Chapter 15's albedo table: E(cos_o, roughness, eta), the share of the light
// one microfacet scattering keeps (tools/microfacet_albedo.cpp computes it,
// albedo_table.glsl reads it). Nodes cos_o = i / (ALBEDO_COS - 1) and
// roughness = j / (ALBEDO_ROUGH - 1); slices 0 .. ALBEDO_ETA - 1: a dielectric
// entered, eta = n2 / n1 from 1 to 3; the next ALBEDO_ETA: left, eta = 1 / that;
// the last: a mirror (F = 1).
#define ALBEDO_COS 32u
#define ALBEDO_ROUGH 32u
#define ALBEDO_ETA 32u
#define ALBEDO_ETA_MAX 3.0f
#define ALBEDO_MIRROR_SLICE (2u * ALBEDO_ETA)
#define ALBEDO_SLICES (2u * ALBEDO_ETA + 1u)
#define ALBEDO_ENTRIES (ALBEDO_SLICES * ALBEDO_ROUGH * ALBEDO_COS)
// the index of refraction n2 / n1 of a dielectric slice
RG_INLINE float albedoSliceEta(uint slice) {
    uint k = slice % ALBEDO_ETA;
    float eta = 1.0f + (ALBEDO_ETA_MAX - 1.0f) * float(k) / float(ALBEDO_ETA - 1u);
    return slice < ALBEDO_ETA ? eta : 1.0f / eta;
}

// A branch of a ray tree still to trace (chapter 10).
struct Branch {
    vec3 origin;
    uint depth;       // bounces so far; chapter 13 sets BRANCH_SPECTRAL above them
    vec3 direction;
    // how far its ray can go: twice the radius when it starts inside a sphere
    float tMax;
    vec3 throughput;  // the share of the pixel's light this branch carries
    // chapter 13: the media the ray is inside (shaders/common/media.glsl)
    uint media;
};
RG_SIZE(Branch, 48);
// chapter 13: the branch has met dispersion, its light is one wavelength's
#define BRANCH_SPECTRAL 0x80000000u
// chapter 15: the branch's path from the camera ray, a bit per bounce (1:
// refracted), between its depth (up to 4095, below) and BRANCH_SPECTRAL
#define BRANCH_PATH_SHIFT 12u
#define BRANCH_PATH_MASK 0x0FFFF000u
// The name a branch's sample points are drawn by (ray_tree.glsl): its depth
// and path laid out as when the depth had 8 bits, so pictures made then
// stay the same; deeper branches share bits, which only renames them.
RG_INLINE uint branchName(uint depth, uint path) {
    return depth | (path >> (BRANCH_PATH_SHIFT - 8u));
}
#ifdef __cplusplus
static_assert(ROULETTE_MAX_DEPTH < (1u << BRANCH_PATH_SHIFT),
              "a branch's depth fits below its path");
#endif

// A pixel whose ray tree goes on past its first hit, queued by chapter 10's
// first launch for the second.
struct QueuedTree {
    Branch stack[2];  // the first hit's refracted and reflected branches
    vec3 radiance;    // the light gathered at the first hit
    uint pixel;       // y * width + x
    uint top;         // branches on the stack
    uint rays;        // rays traced so far
    uint coneStart;   // the tree's Tree::coneStart, its float's bits (ch 12)
    uint pad1;
};
RG_SIZE(QueuedTree, 128);

// The queue's first 16 bytes: the second launch's VkTraceRaysIndirectCommandKHR
// (count, 1, 1), whose width the first launch counts up, then the capacity.
#define TREE_QUEUE_HEADER_BYTES 16u

// ---- Chapter 14: the caustic photon map ------------------------------------
// A photon stored where it landed on a diffuse surface after at least one
// mirror or glass: its power (watts, already divided by the photons emitted)
// and the side of the surface it arrived from.
struct Photon {
    vec3 position;
    uint normal;  // packSnorm4x8 of the unit normal on the side it came from
    vec3 power;
    uint unused;
};
RG_SIZE(Photon, 32);

// Where photons are aimed (a projection map, Jensen 1996): for each light
// and each glass or mirror, the bounding sphere of that object.
struct PhotonEmitter {
    vec4 target;  // the bounding sphere's centre, radius (world)
    uint light;     // index into lights[]
    // a sun's photons start this far before the sphere's centre, beyond
    // every object on their way (at most 1000 radii: float's precision)
    float backoff;
    // this emitter's share of the photons, and the running sum of the
    // shares up to and including it
    float probability;
    float cumulative;
};
RG_SIZE(PhotonEmitter, 32);

// The photon map's first bytes; the rest is reached by device address.
// `cells` is the hash grid: cellCount counts, then (after the prefix sum
// and the scatter) where each cell's photons end in `sorted`.
struct PhotonMapHeader {
    uint stored;        // photons stored this frame (atomic; may pass capacity)
    uint capacity;
    uint cellCount;     // a power of two
    uint emitterCount;
    uvec2 photons;      // Photon[capacity], in the order they were stored
    uvec2 sorted;       // Photon[capacity], by cell
    // uint[cellCount], then uint[cellCount / GRID_SCAN_BLOCK] for the prefix sum
    uvec2 cells;
    uvec2 emitters;     // PhotonEmitter[emitterCount]
    // the fates of the frame's photons, counted (the report; energy tests):
    uint escaped;       // left the scene
    uint lost;          // stopped by the bounce or pass limit
    // --gather-defer (gather.glsl's gather_defer): the crowded cells' gathers
    // the camera rays left for gather_deferred.comp this frame (atomic; may
    // pass deferCapacity: those past it were gathered in place)
    uint deferred;
    uint deferCapacity;
    uvec2 requests;     // GatherRequest[deferCapacity]
    uvec2 heads;        // uint[target pixels]: a pixel's last request (~0u: none)
};
RG_SIZE(PhotonMapHeader, 80);

// A crowded cell's gather, left by a camera ray for gather_deferred.comp:
// the point, its normal, the cell's bucket, and what the ray multiplies the
// irradiance by; the pass replaces `scale` with the light it brings.
struct GatherRequest {
    vec3 position;
    uint bucket;
    vec3 normal;
    uint pixel;  // y * the target's width + x
    vec3 scale;
    uint next;   // the same pixel's request before this one (~0u: none)
};
RG_SIZE(GatherRequest, 48);

// The grid's compute shaders' push constants.
struct GridPush {
    uvec2 photonMap;
    float cellSize;  // twice the gathering radius: a gather reads 2x2x2 cells
    uint unused;
};
RG_SIZE(GridPush, 16);
// gather_deferred.comp's and gather_resolve.comp's push constants
struct DeferPush {
    uvec2 photonMap;
    float radius;        // this frame's gathering radius
    float resolveScale;  // the light's factor into the picture: exposure / frames
};
RG_SIZE(DeferPush, 16);
#define DEFER_GROUP_SIZE 64  // invocations that share one deferred gather
#define GRID_GROUP_SIZE 128  // invocations per workgroup (every device has 128)
// the prefix sum's buckets per invocation, and per workgroup (grid_scan.comp)
#define GRID_SCAN_RUN 8
#define GRID_SCAN_BLOCK (GRID_GROUP_SIZE * GRID_SCAN_RUN)

#ifdef __cplusplus
}  // namespace rg::gpu
#endif
#endif  // RG_HOST_DEVICE_H
