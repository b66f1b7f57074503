// The CPU reference renderer: the same scene, camera and shading as the GPU
// chapters, written again in double precision with none of the GPU's code
// (its own camera basis, intersections and sky filter), so that comparing
// the two finds errors in either. One ray per pixel centre, or with
// --antialias the GPU's own points in the pixel (sampling.h): where to
// sample is the input both share, not a rule under test.
#pragma once
#include "core/image.h"
#include "scene/scene.h"

#include <glm/glm.hpp>

#include <memory>
#include <vector>

namespace rg {

// What the reference computes: the shading of one chapter.
enum class ReferenceStage {
    Normals = 4,
    Ambient = 5,
    Diffuse = 6,
    Specular = 7,
    Reflection = 8,
    Fresnel = 9,
    Refraction = 10,
    Rough = 11,
    Media = 13,
    Caustics = 14,  // chapter 13's media, lights in watts, and a photon map
    Frosted = 15    // and rough surfaces as microfacets
};  // chapter 12 renders Rough on meshes

// Chapter 13: the media a ray is inside, the last entered at the back
// (the GPU's media.glsl keeps four; so does this).
struct MediumStack {
    std::vector<uint32_t> materials;
    double wavelength = 0;  // nm: the path's, once it has met dispersion; 0 before
    // The pixel's wavelengths, one per accumulated frame as the GPU draws
    // them: where the path first meets dispersion, its light is their mean.
    const std::vector<double>* wavelengths = nullptr;
};

// Chapter 15: which branch of which pixel's tree in which frame a ray is,
// for its rough hit's sample point (ray_tree.glsl's branchSample).
struct BranchId {
    uint32_t seed = 0;         // the pixel's (its stream kFacetStream)
    uint32_t accumulated = 0;  // the frame's index in the average
    uint32_t path = 0;         // a bit per bounce from the camera ray, above bit 8
};

// Chapter 13: the wavelength (nm) of pixel (x, y)'s paths in frame k of an
// accumulation that began at frame `first`, drawn as the GPU's spectrum.glsl
// does (the radical inverse of k, shifted by a hash of the pixel), so that
// the reference integrates over the same wavelengths as the image it checks.
double referencePathWavelength(uint32_t x, uint32_t y, uint32_t first, uint32_t k);

// Chapter 13: what one wavelength (nm) is worth in each linear sRGB channel,
// the CIE 1931 matching functions (Wyman, Sloan and Shirley's fit) to sRGB
// over their mean across 380-780 nm, computed here in double.
glm::dvec3 referenceSpectralWeight(double nm);

struct ReferenceSettings {
    ReferenceStage stage = ReferenceStage::Normals;
    int maxDepth = 1;
    int fresnelMode = 0;
    int samples = 1024;  // chapter 11: stratified samples per rough hit (a square number)
    // chapter 11: another seed gives an independent estimate (to measure its error)
    uint64_t seed = 0;
    // chapter 13: >= 380, every path at this wavelength (nm); else:
    double wavelength = 0;
    uint32_t frames = 1;      // the frames accumulated, one wavelength per path in each,
    uint32_t firstFrame = 0;  // from this frame on
    double exposure = 1;      // 2^EV: the image is the radiance times this (--exposure)
    // --antialias: each pixel is the mean over the first `frames` points of
    // its jitter sequence (the GPU's, sampling.glsl), one camera ray each.
    bool antialias = false;
    // Chapter 14: the gathering radius of each frame averaged (the GPU's
    // Knaus-Zwicker sequence); a diffuse point's caustic light is the mean of
    // the photon map's estimates at these radii.
    std::vector<double> photonRadii;
    // Photons from each (light, glass) pair: a stratified grid of this many
    // a side, each split at every surface by its Fresnel shares (photons.cpp).
    int photonGrid = 1000;
    // Chapter 14's --caustics transmit: shadow rays pass glass unbent, keeping
    // 1 - F at each surface and Beer-Lambert between (and no photons).
    bool transmitShadows = false;
    // Chapter 15's --multiple-scattering: rough lobes compensated with the
    // albedo table (scene/microfacet_albedo.h), as rough_surface.glsl does.
    bool multipleScattering = false;
    // Chapter 15's --roulette: past maxDepth one path goes on, ended by
    // Russian roulette, up to this depth (ray_tree.glsl's roulette)
    int maxPathDepth = 0;
    // Chapter 15's --rough-branches one: past the camera ray's hit a rough
    // surface sends one branch on (ray_tree.glsl's oneBranch)
    bool oneRoughBranch = false;
};

class ReferencePhotons;

struct ReferenceHit {
    double t = -1;          // < 0: miss
    glm::dvec3 normal{0};   // world, unit, out of the shape
    // world, unit shading normal on the side of `normal` (a mesh's interpolated one)
    glm::dvec3 shading{0};
    uint32_t object = 0;
    bool frontFace = true;
    // how far origin + t * direction may lie from the surface (its rounding)
    double error = 0;
    // a textured mesh's base colour texture at the hit (chapter 12), else 1
    glm::dvec3 tint{1};
    // its metal-roughness texture's roughness (G) and metalness (B), else 1
    double roughnessTexel = 1, metalnessTexel = 1;
    // a mesh's triangle and the hit's barycentric weights (textureAt)
    uint32_t triangle = 0;
    glm::dvec3 weights{0};
};

// Chapter 12's ray cone (mesh.rchit's coneLod): the angle one pixel spans,
// and how far from the eye the ray's cone starts (0 for a camera ray, then
// the camera ray's hit distance, as the GPU's ray tree).
struct RayCone {
    double spread = 0;
    double start = 0;
};

class ReferenceRenderer {
public:
    explicit ReferenceRenderer(const Scene& scene);
    // The closest hit along origin + t * direction with t in (tMin, tMax),
    // through a BVH over the objects' boxes; of equally close hits, the
    // object listed first.
    ReferenceHit trace(const glm::dvec3& origin, const glm::dvec3& direction, double tMin,
                       double tMax) const;
    // The same by testing every object (what the BVH must agree with: tests).
    ReferenceHit traceLinear(const glm::dvec3& origin, const glm::dvec3& direction,
                             double tMin, double tMax) const;
    glm::dvec3 sky(const glm::dvec3& direction) const;
    // A texture at a texture coordinate and level of detail (log2 of texels
    // a pixel spans): the sampler's wrap, filters and mip levels, written
    // again in double (texture.glsl's sampleTexture).
    static glm::dvec3 sampleTexture(const Texture& texture, const glm::dvec2& uv,
                                    double lod = 0);
    // Its alpha at level 0 (chapter 12's alpha test); 1 for an opaque image.
    static double sampleAlpha(const Texture& texture, const glm::dvec2& uv);
    // The material of a hit: its ambient and diffuse colours times hit.tint,
    // or glTF's mapping redone with the textures' values (chapter 12).
    Material hitMaterial(const ReferenceHit& hit) const;
    // A traced hit's textures (chapter 12): into hit.tint, its metal-roughness
    // values and hit.shading, at the level the ray's cone chooses.
    void textureAt(ReferenceHit& hit, const glm::dvec3& direction,
                   const RayCone& cone) const;
    // log2 of the cone's footprint in texture coordinates at a mesh's hit.
    double coneLod(const ReferenceHit& hit, const glm::dvec3& direction,
                   const RayCone& cone) const;
    // The angle one pixel spans at the image's centre, for `height` rows.
    double pixelSpread(uint32_t height) const;
    // Through the point `offset` of pixel (x, y): (0.5, 0.5) its centre.
    void cameraRay(uint32_t x, uint32_t y, uint32_t width, uint32_t height,
                   glm::dvec3& origin, glm::dvec3& direction,
                   glm::dvec2 offset = glm::dvec2(0.5)) const;
    // Pixel (x, y): one ray through its centre, or with settings.antialias
    // the mean of the GPU's frames' rays. Chapter 11 also returns the
    // standard error of its rough-reflection estimate in `stdError` (0 elsewhere).
    glm::dvec3 shade(const ReferenceSettings& settings, uint32_t x, uint32_t y,
                     uint32_t width, uint32_t height, double* stdError = nullptr) const;
    // One camera ray through `offset` of the pixel; `frame`: which of the
    // frames' wavelengths it carries (chapter 13), -1: all of them.
    glm::dvec3 shadeRay(const ReferenceSettings& settings, uint32_t x, uint32_t y,
                        uint32_t width, uint32_t height, glm::dvec2 offset, int frame,
                        double* stdError) const;
    // Radiance arriving along a ray (chapters 05-10), following reflections
    // and refractions up to the depth limit.
    glm::dvec3 radiance(const ReferenceSettings& settings, const glm::dvec3& origin,
                        const glm::dvec3& direction, int depth,
                        const glm::dvec3& throughput, const RayCone& cone = {}) const;
    // Chapter 13: the same inside `media`; `passes` counts the surfaces
    // crossed where no medium changes (at most 256 per camera ray, as the GPU).
    glm::dvec3 radiance(const ReferenceSettings& settings, const glm::dvec3& origin,
                        const glm::dvec3& direction, int depth,
                        const glm::dvec3& throughput, const MediumStack& media,
                        int& passes, const RayCone& cone = {},
                        const BranchId& branch = {}) const;
    // n: the geometric normal (shadow rays leave along it); ns: the shading
    // normal. Ambient and diffuse light are weighted by `local`, the
    // highlight by `highlight` (a dielectric's share F of it, chapter 09 on).
    glm::dvec3 localShading(const ReferenceSettings& settings, const Material& m,
                            const glm::dvec3& p, double error, const glm::dvec3& n,
                            const glm::dvec3& ns, const glm::dvec3& v, double local = 1,
                            double highlight = 1) const;
    // Renders every pixel on all cores. For chapter 11 each pixel's alpha
    // holds the standard error of its estimate (the reference's own error).
    FloatImage render(const ReferenceSettings& settings, uint32_t width,
                      uint32_t height) const;
    // Where a secondary ray leaving p (normal n) starts: moved along n by the
    // hit's own error bound, as the GPU's offsetRay, but the bound of double
    // precision (about 1e-15 of the numbers involved, where the GPU's is 1e-6):
    // the reference stays close to exact geometry, so comparing against it
    // shows where the GPU's offsets change the picture.
    glm::dvec3 secondaryOrigin(const glm::dvec3& p, double error,
                               const glm::dvec3& n) const;
    // True when nothing lies between `from` and the light (in double precision).
    bool lightVisible(const glm::dvec3& from, const glm::dvec3& light) const;
    // Camera rays ignore hits closer than this to the eye (the GPU's eyeTmin).
    double eyeTmin() const { return scene_.eyeTmin; }
    // Chapter 14: direct light in watts (Lambert's kd / pi, normalized
    // Blinn-Phong) with the shares of chapter 09, as the page teaches it.
    glm::dvec3 directLight(const ReferenceSettings& settings, const Material& m,
                           const glm::dvec3& p, double error,
                           const glm::dvec3& n, const glm::dvec3& ns, const glm::dvec3& v,
                           double local, double highlight) const;
    // Chapter 15: the lights' glints on a rough surface of roughness^2 alpha
    // between indices n1 and n2 (ray_tree.h's roughLobe toward each light),
    // those that add at least 1e-4 to the pixel through `throughput`.
    glm::dvec3 roughGlints(const ReferenceSettings& settings, const Material& m,
                           double alpha, double n1, double n2, const glm::dvec3& p,
                           double error, const glm::dvec3& n, const glm::dvec3& ns,
                           const glm::dvec3& v, const glm::dvec3& throughput) const;
    // True when nothing lies between `from` and the sun, in direction l.
    bool sunVisible(const glm::dvec3& from, const glm::dvec3& l) const;
    // --caustics transmit: what passes from `from` along unit l up to tMax,
    // through every glass surface on the way (1 - F each, Beer-Lambert inside).
    glm::dvec3 lightArriving(const ReferenceSettings& settings, const PointLight& light,
                             const glm::dvec3& from, const glm::dvec3& l) const;
    glm::dvec3 transmittedLight(const ReferenceSettings& settings, glm::dvec3 from,
                                const glm::dvec3& l, double tMax) const;
    const Scene& scene() const { return scene_; }

private:
    // Tests object i; updates `best` when it is hit closer (or as close and listed
    // earlier).
    void hitObject(uint32_t i, const glm::dvec3& origin, const glm::dvec3& direction,
                   double tMin, double tMax, ReferenceHit& best) const;
    // Chapter 12: a mesh's textures at the hit of `triangle` with barycentric
    // weights `w` and footprint (coneLod), into hit.tint, its metal-roughness
    // values and hit.shading (the normal texture's; textures.cpp).
    void textureHit(const Object& obj, uint32_t triangle, const glm::dvec3& w,
                    double footprint, ReferenceHit& hit) const;
    void buildBvh();

public:
    // The reference's own acceleration (thesis 2.2.1 on the CPU): a binary
    // tree of boxes, median splits on the longest axis, up to 4 items a leaf;
    // one over the objects, and one per mesh over its triangles (chapter 12).
    struct BvhNode {
        glm::dvec3 lo, hi;
        uint32_t first = 0, count = 0;  // a leaf: items[first, first + count)
        // an inner node: children at index + 1 and `right`
        uint32_t right = 0;
    };
    struct Bvh {
        std::vector<BvhNode> nodes;
        std::vector<uint32_t> items;
    };
    // A mesh in double, with its triangles' tree (object space).
    struct MeshData {
        std::vector<glm::dvec3> vertices, normals;
        std::vector<glm::dvec2> texcoords;
        std::vector<uint32_t> indices;
        Bvh bvh;
        double size = 0;  // the largest vertex coordinate's magnitude
    };
    struct TriangleHit {
        double t = -1;
        uint32_t triangle = 0;
        glm::dvec3 weights{0};  // barycentric weights of the triangle's three vertices
        // the winding: counter-clockwise seen from the ray's origin
        bool front = true;
    };
    // Watertight ray-triangle test (Woop, Benthin and Wald 2013, as PBRT-v4):
    // closest hit in (tMin, tMax) over the mesh's tree, in object space.
    // `counts` (chapter 12's alpha test): a hit counts only if it says so,
    // given the triangle and the weights.
    using HitFilter = std::function<bool(uint32_t triangle, const glm::dvec3& weights)>;
    static TriangleHit intersectMesh(const MeshData& mesh, const glm::dvec3& o,
                                     const glm::dvec3& d, double tMin, double tMax,
                                     const HitFilter& counts = nullptr);
    const MeshData& meshData(uint32_t mesh) const { return meshes_[mesh]; }

private:
    Bvh bvh_;
    std::vector<MeshData> meshes_;

    const Scene& scene_;
    std::vector<glm::dmat4> worldToObject_;
    // |translation| + largest scale: the magnitude of its numbers
    std::vector<double> objectSize_;
    uint32_t skyWidth_ = 0, skyHeight_ = 0;
    // as the GPU's kRayCones: some texture has mip levels (textureAt)
    bool rayCones_ = false;
    // chapter 14: the photon map render() builds before the pixels
    mutable std::shared_ptr<const ReferencePhotons> photons_;
    std::vector<double> sky_;  // linear RGB
};

// Fresnel reflectance, in double (mode as the GPU's: 0 Schlick with f0,
// 1 Schlick with f0 from the IOR, 2 exact), going from index n1 into n2.
double referenceFresnel(int mode, double f0, double cosI, double n1, double n2);

// Roots t0 <= t1 of |o + t d| = 1, in double (the reference's own form).
bool referenceUnitSphere(const glm::dvec3& o, const glm::dvec3& d, double& t0,
                         double& t1);

struct ImageError {
    double rmse = 0;            // linear values, over all pixels and RGB channels
    double maxAbs = 0;          // largest linear difference
    // share of pixels whose display value differs by more than 1/255
    double fracOver1_255 = 0;
    double psnrDb = 0;          // of the display values
    uint64_t nonFinite = 0;     // NaN or Inf pixels in the tested image
};

// Compares `test` against `reference`; writes a heat map (black: equal,
// red to yellow to white: up to 8/255 of display difference) when asked.
ImageError compareImages(const FloatImage& test, const FloatImage& reference,
                         FloatImage* heatMap);

}  // namespace rg
