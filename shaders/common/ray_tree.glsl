// Chapter 10's ray tree, for every chapter after it: how light divides at a
// surface (Fresnel, R + T = 1), and the depth-first stack that follows both
// branches up to the depth limit.
#ifndef RAY_TREE_GLSL
#define RAY_TREE_GLSL
#include "fresnel.glsl"
#include "media.glsl"
#ifdef MICROFACET
#include "rough_surface.glsl"
#endif

#define MAX_DEPTH 8                // --depth is at most this
#define MIN_THROUGHPUT 1e-4        // branches carrying less light are not traced
// chapter 13: surfaces a tree may cross where no medium changes
#define MAX_PASSES 256

// [region split]
struct Split {
    float reflected, refracted, local;  // shares of the light; they sum to 1
    float highlight;                    // the highlight's share: local + a dielectric's F
    float eta;                          // n1 / n2 for Snell's law
};

// Going from index n1 into n2.
Split splitBetween(GpuMaterial m, float n1, float n2, vec3 n, vec3 direction) {
    float transmission = m.params.z;
    // 1 under total internal reflection
    float F = fresnel(push.fresnelMode, m.extra.x, dot(n, -direction), n1, n2);
    Split s;
    s.reflected = transmission * F + (1.0 - transmission) * m.params.y;
    s.refracted = transmission * (1.0 - F);  // R + T = 1 for the dielectric part
    s.local = 1.0 - s.reflected - s.refracted;
    s.highlight = s.local + transmission * F;  // a light's glint is reflection too
    s.eta = n1 / n2;
    return s;
}

// Chapters 09-12: every glass has air outside (chapter 13: media.glsl).
Split splitAt(GpuMaterial m, bool entering, vec3 n, vec3 direction) {
    float ior = m.params.w;
    // Entering: air into the glass; leaving: the ratio inverts. A thin wall
    // (MATERIAL_THIN) has air on both sides: from either, air into glass.
    bool thin = kThinWalls && (m.flags & MATERIAL_THIN) != 0u;
    Split s = entering || thin ? splitBetween(m, 1.0, ior, n, direction)
                               : splitBetween(m, ior, 1.0, n, direction);
    if (thin) s.eta = 1.0;  // crossed unbent
    return s;
}
// [end]

float maxComponent(vec3 v) { return max(v.r, max(v.g, v.b)); }

// [region sides]
// Chapter 12: a mesh shades with its interpolated normal ns, but its surface
// is the flat triangle with normal n. A direction found with ns can end up
// on the wrong side of the triangle: a reflection into the surface, a
// refraction back out of it. Traced as it is, the first would start inside
// the glass as if it had entered, the second outside as if it had left,
// and the medium stack of the path would be wrong from there on. So such a
// direction is found again with n, which always puts it on its own side.
// (For spheres and quads ns = n, and neither test ever fails.)
vec3 reflectedDirection(vec3 d, vec3 n, vec3 ns) {
    vec3 r = reflect(d, ns);
    return dot(r, n) > 0.0 ? r : reflect(d, n);
}
// vec3(0) when even the flat surface reflects totally: the caller gives
// that share to the reflection.
vec3 refractedDirection(vec3 d, vec3 n, vec3 ns, float eta) {
    vec3 t = refract(d, ns, eta);
    if (dot(t, n) < 0.0) return normalize(t);
    t = refract(d, n, eta);
    return t == vec3(0.0) ? t : normalize(t);
}
// [end]

// [region inside_reach]
// A ray that starts inside a sphere of radius r leaves it within a diameter
// (plus its origin's offset from the hit point p and p's rounding): its
// tMax, so that traversal skips every box beyond (a million spheres around).
// r = 0: not a sphere, no bound.
float insideReach(vec3 origin, vec3 p, float r) {
    if (r <= 0.0) return kInfinity;
    return 2.002 * r + distance(origin, p) + 1e-6 * maxComponent(abs(p));
}
// [end]

// [region tree]
// A ray tree being traced depth first: the branches still to trace (at
// most one pending per level), the light gathered so far, rays traced.
// One per invocation, a global: the functions below share it instead of
// copying its stack in and out as a parameter.
struct Tree {
    Branch stack[MAX_DEPTH + 2];
    int top;
    vec3 radiance;
    uint rays;
    uint passes;  // chapter 13: surfaces crossed without a change of medium (MAX_PASSES)
    // chapter 13: the one wavelength (nm) of the branches that met dispersion
    float wavelength;
    // chapter 12: the camera ray's hit distance, where every deeper branch's
    // ray cone starts (traceClosest; the lengths of the segments between are
    // left out, and so are the curvatures that widen or narrow a cone)
    float coneStart;
#ifdef MICROFACET
    uint seed;  // chapter 15: the pixel's, for its branches' sample points
#endif
};
Tree tree;

#ifdef MICROFACET
// [region branch_sample]
// Chapter 15: each branch carries its path from the camera ray, a bit per
// bounce (1: refracted), above its depth; with the depth it names the
// branch, whose rough hit draws point `accumulated` of its own Sobol
// sequence (sampling.glsl): frame after frame, each branch of the tree
// goes on with its own low-discrepancy points, and the reference draws
// the same.
// The pixel's seed comes from a stream of its own (as chapter 04's jitter),
// not from the frame an average began on: an average started again (the
// view moved back) draws the same facets, and so does the reference.
#define FACET_STREAM 0xFACE75EDu  // no frame number reaches it
// (BRANCH_PATH_SHIFT and _MASK: host_device.h)
uint childPath(uint path, uint refracted) {
    return ((path << 1u) | (refracted << BRANCH_PATH_SHIFT)) & BRANCH_PATH_MASK;
}
uint branchSequence(uint depth, uint path) {
    return pcgHash(tree.seed ^ pcgHash(branchName(depth, path)));
}
vec2 branchSample(uint depth, uint path) {
    return sobolPoint(push.accumulated, branchSequence(depth, path));
}
// [end]

// [region roulette]
// Chapter 15: the depth limit cuts off light that is still bouncing, most
// inside rough glass (the furnace on page 15). With --roulette on, past
// the limit a branch goes on as one path instead of two: it follows the
// refracted child with probability T / (R + T), else the reflected one,
// and carries R + T either way; then Russian roulette ends it with
// probability 1 - q, q its throughput's largest part (at most 1), and a
// survivor carries its throughput / q. Both choices keep the mean (PBRT-v4
// 2.2.4); the stack never grows, and paths end by ROULETTE_MAX_DEPTH.
// Names past 16 bounces keep their last 16 turns (BRANCH_PATH_MASK).
#define ROULETTE_SALT 0x0B0E7712u  // the choice's sequence, beside the facet's
vec2 choicePoint(uint depth, uint path) {
    return sobolPoint(push.accumulated, branchSequence(depth, path) ^ ROULETTE_SALT);
}
// One child instead of two, u in [0,1): the refracted with probability
// t / (t + r), else the reflected, carrying both children's light.
void keepOneChild(float u, inout vec3 refracted, inout vec3 reflected) {
    float t = maxComponent(refracted), r = maxComponent(reflected);
    vec3 carried = refracted + reflected;
    bool refract = u * (t + r) < t;
    refracted = refract ? carried : vec3(0.0);
    reflected = refract ? vec3(0.0) : carried;
}
bool roulette(uint depth, uint path, inout vec3 refracted, inout vec3 reflected) {
    if (depth >= push.maxPathDepth) return false;
    if (maxComponent(refracted) + maxComponent(reflected) <= 0.0) return false;
    vec2 u = choicePoint(depth, path);
    float q = min(1.0, maxComponent(refracted + reflected));
    if (u.y >= q) return false;
    keepOneChild(u.x, refracted, reflected);
    refracted /= q, reflected /= q;
    return true;
}
// [end]

// [region one_branch]
// Chapter 15: a rough surface scatters its two branches over its lobe, so
// neighbouring pixels' rays no longer travel together, and each costs
// several times a smooth ray on a GPU (performance page). Past the camera
// ray's own hit (the surface the viewer sees stays sharp), --rough-branches
// one sends one branch on: the refracted with probability T / (R + T),
// else the reflected, carrying R + T either way, which keeps the mean
// (PBRT-v4's rough dielectric chooses the same way). The choice is
// roulette's, drawn from the same point.
void oneBranch(uint depth, uint path, inout vec3 refracted, inout vec3 reflected) {
    if (maxComponent(refracted) <= 0.0 || maxComponent(reflected) <= 0.0)
        return;  // one branch already
    keepOneChild(choicePoint(depth, path).x, refracted, reflected);
}
// [end]
#else
uint childPath(uint path, uint refracted) { return 0u; }
#endif
// what a branch's depth field holds besides its depth
#ifdef MICROFACET
const uint kBranchFlags = BRANCH_SPECTRAL | BRANCH_PATH_MASK;
#else
const uint kBranchFlags = BRANCH_SPECTRAL;
#endif

void plantTree(vec3 origin, vec3 direction, uint depth, vec3 throughput, uint rays) {
    // in air (chapter 13)
    tree.stack[0] = Branch(origin, depth, direction, kInfinity, throughput, 0u);
    tree.top = 1;
    tree.passes = 0u;
    tree.radiance = vec3(0.0);
    tree.rays = rays;
    tree.coneStart = 0.0;
}

// Traces the branch on top of the stack, pushes its own reflected and
// refracted branches, and adds the light it brings.
void growBranch() {
    int top = --tree.top;
    // The ray first, read from the stack; the rest of the branch after the
    // trace, so that it need not stay alive across it (performance page).
    // Depth 0: a camera ray.
    bool camera = (tree.stack[top].depth & ~kBranchFlags) == 0u;
    traceClosest(tree.stack[top].origin, camera ? eyeTmin() : 0.0,
                 tree.stack[top].direction, tree.stack[top].tMax,
                 camera ? 0.0 : tree.coneStart);
    Branch b = tree.stack[top];
    // chapter 13: its light is one wavelength's
    uint spectral = b.depth & BRANCH_SPECTRAL;
    b.depth &= ~BRANCH_SPECTRAL;
#ifdef MICROFACET
    uint path = b.depth & BRANCH_PATH_MASK;  // chapter 15: which branch this is
    b.depth &= ~BRANCH_PATH_MASK;
#else
    uint path = 0u;
#endif
    if (camera) tree.coneStart = payload.t;
    ++tree.rays;
    vec3 throughput = b.throughput;
#ifdef NESTED_MEDIA
    // chapter 13: absorbed on the way (Beer-Lambert)
    throughput *= transmittance(b.media, payload.t);
#endif
    if (payload.t < 0.0) {
        tree.radiance += throughput * payload.radiance;
        return;
    }
    GpuMaterial m = hitMaterial();  // a mesh's texture tints it (ch 12)
    vec3 n = facingNormal(payload.normal, b.direction);
    // = n but on meshes
    vec3 ns = hitFacingShading(b.direction);
    vec3 p = payload.position;
    float e = payload.error;
    float radius = objects[payload.object].radius;  // 0: not a sphere
    bool entering = payload.frontFace == 1u;  // from the hit kind on meshes (chapter 12)
    // air outside (ch 10)
    float n1 = entering ? 1.0 : m.params.w, n2 = entering ? m.params.w : 1.0;
    uint beyond = b.media;  // the media of a ray that crosses here (chapter 13)
    // [region thin]
    // A thin-walled surface (glTF's default for transmission without a
    // volume, KHR_materials_volume): the same medium on both sides. Fresnel
    // from that medium into the material's index, from either side; what
    // crosses goes on unbent, and no medium begins or ends.
    bool thin = kThinWalls && (m.flags & MATERIAL_THIN) != 0u;
    if (thin) n1 = mediumIor(currentMedium(b.media)), n2 = m.params.w;  // air: 1
    // [end]
    // [region media]
#ifdef NESTED_MEDIA
    // chapter 13: a medium's surface; which two media meet here?
    if (m.params.z > 0.0 && !thin) {
        Boundary boundary =
            boundaryAt(b.media, objects[payload.object].material, entering);
        // no surface: the ray goes on into its new media, as deep as before
        if (!boundary.real) {
            vec3 o = secondaryOrigin(p, e, -n);
            float tMax = entering ? insideReach(o, p, radius) : kInfinity;
            if (tree.passes++ < MAX_PASSES)
                tree.stack[tree.top++] = Branch(o, b.depth | spectral | path,
                                                b.direction, tMax, throughput,
                                                boundary.beyond);
            return;
        }
        n1 = boundary.n1, n2 = boundary.n2, beyond = boundary.beyond;
        // [region dispersion]
        if (mediumDispersion(boundary.from) != vec2(0.0) ||
            mediumDispersion(boundary.to) != vec2(0.0)) {
            // The indices at the path's wavelength. The first time, the branch's
            // light becomes that wavelength's (spectrum.glsl), unless every path
            // has the one wavelength of --wavelength.
            n1 = mediumIorAt(boundary.from, tree.wavelength);
            n2 = mediumIorAt(boundary.to, tree.wavelength);
            bool oneWavelength = push.wavelength >= SPECTRUM_MIN_NM;
            if (spectral == 0u && !oneWavelength)
                throughput *= spectralWeight(tree.wavelength);
            spectral = BRANCH_SPECTRAL;
        }
        // [end]
    }
#endif
    // [end]
    Split s = splitBetween(m, n1, n2, ns, b.direction);
#ifdef MICROFACET
    // [region rough_branches]
    // Chapter 15: a rough surface's two branches leave about one visible
    // normal, with the shares of rough_surface.glsl; the lights' glints are
    // its lobe's (roughLight below), the local model keeps the local part.
    float alpha = roughAlpha(m);
    RoughSplit rough;
    if (alpha > 0.0) {
        rough = roughSplit(m, alpha, n1, n2, n, ns, b.direction,
                           branchSample(b.depth, path));
        s.reflected = rough.reflectedShare, s.refracted = rough.refractedShare;
        s.highlight = s.local;
    }
    // [end]
#endif
    vec3 tr = throughput * s.refracted, rf = throughput * s.reflected;
    // [region one_branch_call]
#ifdef MICROFACET
    if (alpha > 0.0 && b.depth > 0u && push.oneRoughBranch != 0u)
        oneBranch(b.depth, path, tr, rf);  // chapter 15: past the camera ray's hit
#endif
    // [end]
    // [region depth_limit]
    if (b.depth >= push.maxDepth) {  // the depth limit: deeper light is lost ...
#ifdef MICROFACET
        if (!roulette(b.depth, path, tr, rf))  // ... or one path goes on (chapter 15)
#endif
            tr = rf = vec3(0.0);
    }
    // [end]
    // [region refract]
    if (maxComponent(tr) >= MIN_THROUGHPUT) {
        // Snell: n1 sin(i) = n2 sin(t); GLSL's refract takes n facing the ray and n1 /
        // n2.
        vec3 t = thin ? b.direction : refractedDirection(b.direction, n, ns, s.eta),
             o = secondaryOrigin(p, e, -n);
#ifdef MICROFACET
        if (alpha > 0.0) t = rough.refracted;
#endif
        // into the sphere
        float tMax = entering && !thin ? insideReach(o, p, radius) : kInfinity;
        uint depth = (b.depth + 1u) | spectral | childPath(path, 1u);
        if (t != vec3(0.0))
            tree.stack[tree.top++] = Branch(o, depth, t, tMax, tr, beyond);
        else rf += tr;  // only a mesh's flat triangle can reflect it all (sides above)
    }
    // [end]
    if (maxComponent(rf) >= MIN_THROUGHPUT) {
        vec3 o = secondaryOrigin(p, e, n);
        // back into it
        float tMax = entering || thin ? kInfinity : insideReach(o, p, radius);
        vec3 r = reflectedDirection(b.direction, n, ns);
#ifdef MICROFACET
        if (alpha > 0.0) r = rough.reflected;
#endif
        uint depth = (b.depth + 1u) | spectral | childPath(path, 0u);
        tree.stack[tree.top++] = Branch(o, depth, r, tMax, rf, b.media);
    }
    // The light at this hit last, once the branches are on the stack: fewer
    // numbers are alive across its shadow rays (performance page).
#ifdef PHOTON_MAP
    // [region caustic_light]
    // chapter 14: direct light in watts, and the caustic light of the
    // photons that landed here, reflected by Lambert's kd / pi
#ifdef MICROFACET  // chapter 15: with the glints of a rough surface
    if (alpha > 0.0 || s.highlight > 0.0)
        tree.radiance += throughput * roughLight(m, alpha, n1, n2, p, e, n, ns,
                                                 -b.direction, s.local, s.highlight,
                                                 throughput, tree.rays);
#else
    if (s.highlight > 0.0)
        tree.radiance += throughput * directLight(m, p, e, n, ns, -b.direction, s.local,
                                                  s.highlight, tree.rays);
#endif
    if (s.local > 0.0) {
        vec3 scale = throughput * s.local * m.kd.rgb / kPi;
        tree.radiance += scale * causticIrradiance(p, n, scale);
    }
    // [end]
#else
    if (s.highlight > 0.0)  // >= local: the local model's two parts with their shares
        tree.radiance += throughput * surfaceLight(m, p, e, n, ns, -b.direction, s.local,
                                                   s.highlight, tree.rays);
#endif
}

// The light arriving along one ray, following reflections and refractions
// to the depth limit; `rays` counts every ray traced; `coneStart`: the
// camera ray's hit distance (chapter 12's ray cones).
vec3 traceTree(vec3 origin, vec3 direction, uint depth, vec3 throughput,
               inout uint rays, float coneStart) {
    plantTree(origin, direction, depth, throughput, rays);
    tree.coneStart = coneStart;
    while (tree.top > 0) growBranch();
    rays = tree.rays;
    return tree.radiance;
}
// [end]
#endif
