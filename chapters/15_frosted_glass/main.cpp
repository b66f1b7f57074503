// Chapter 15 - Frosted glass. Chapter 11 blurred mirrors the thesis's way
// (4.3), by spreading reflection rays over a cone: no physical material, no
// rough transmission. Here a rough surface is a field of tiny mirror-smooth
// facets (microfacets) whose normals follow the GGX distribution; a ray
// meets one facet, drawn from the normals it can see, and reflects and
// refracts there with chapter 13's exact Fresnel (Walter et al. 2007). The
// light that leaves through glass spreads: frosted glass, and through
// chapter 14's photons, a soft caustic. Roughness 0 is chapter 14 exactly.
#include "app/app.h"
#include "chapter/rt_options.h"
#include "photons/photon_pass.h"
#include "scene/microfacet_albedo.h"
#include "vulkan/resources.h"

// [region compensation]
// The light single scattering loses, given back (page 15, "Energy"): the
// albedo table, computed at build time (tools/microfacet_albedo.cpp), goes
// to the GPU once; each frame's push constants point the shaders at it
// (rough_surface.glsl's compensation) and the reference does the same.
rg::FramePass withCompensation(rg::FramePass pass, const rg::FramePassContext& c,
                               const int& multipleScattering) {
    rg::Buffer table = rg::createDeviceBuffer(
        c.app.gpu, c.app.deletion, rg::kMicrofacetAlbedo, sizeof rg::kMicrofacetAlbedo,
        VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT);
    auto record = pass.record;
    pass.record = [=, &multipleScattering](VkCommandBuffer cmd, rg::gpu::RtPush& push,
                                           rg::FrameChange change) {
        push.multipleScattering = multipleScattering == 0;  // "on"
        push.albedoTable = {uint32_t(table.address), uint32_t(table.address >> 32)};
        if (record) record(cmd, push, change);
    };
    auto reference = pass.reference;
    pass.reference = [=, &multipleScattering](rg::ReferenceSettings& r) {
        r.multipleScattering = multipleScattering == 0;
        if (reference) reference(r);
    };
    return pass;
}
// [end]

// [region roulette]
// --roulette on (page 15, "Past the depth limit"): each frame's push
// constants and the reference let a path go on past --depth, one branch
// at a time, until Russian roulette ends it (ray_tree.glsl's roulette);
// --rough-branches one: one branch past the camera ray's hit too.
struct PathOptions {
    int roulette = 0;       // on
    int roughBranches = 1;  // one
    int maxBounces = int(ROULETTE_MAX_DEPTH);
};
rg::FramePass withPathOptions(rg::FramePass pass, const PathOptions& o) {
    auto record = pass.record;
    pass.record = [=, &o](VkCommandBuffer cmd, rg::gpu::RtPush& push,
                          rg::FrameChange change) {
        if (o.roulette == 0) push.maxPathDepth = uint32_t(o.maxBounces);  // "on"
        push.oneRoughBranch = o.roughBranches == 1;
        if (record) record(cmd, push, change);
    };
    auto reference = pass.reference;
    pass.reference = [=, &o](rg::ReferenceSettings& r) {
        r.maxPathDepth = o.roulette == 0 ? o.maxBounces : 0;
        r.oneRoughBranch = o.roughBranches == 1;
        if (reference) reference(r);
    };
    return pass;
}
// [end]

int main(int argc, char** argv) {
    // chapter 14's photon pass, its photons through rough surfaces too
    rg::PhotonChapter photons = rg::photonChapter("15_frosted_glass/photon.rgen");
    int multipleScattering = 0;  // on
    PathOptions paths;
    return rg::runRtChapter(argc, argv, {
        .name = "15_frosted_glass",
        .description = "RayGlass chapter 15: frosted glass, microfacet reflection and "
                       "transmission",
        .title = "RayGlass 15: frosted glass",
        .stage = rg::ReferenceStage::Frosted,
        .meshes = true,
        // Frosted, half-frosted and clear glass balls and a rough mirror in sunlight.
        .scene = "frosted",
        .options = [&](rg::Params& params, rg::RtChapterSettings& s) {
            rg::addDepthOption(params, s, 8);
            s.fresnelMode = 2;  // exact, as chapter 13
            rg::addSpectralOptions(params, s);
            params.choice("--sampling", s.facetSampling,
                          "How a rough hit draws its branches: visible normals, or "
                          "chapter 11's cone mixed with them (page 15's comparison; "
                          "the reference draws visible normals)",
                          {"visible", "cone"});
            params.choice("--multiple-scattering", multipleScattering,
                          "Give back the light single scattering between the facets "
                          "loses (the albedo table), or leave it lost",
                          {"on", "off"});
            params.choice("--roulette", paths.roulette,
                          "Past --depth, let one path go on until Russian roulette "
                          "ends it, or cut the light off there",
                          {"on", "off"});
            params.integer("--max-bounces", paths.maxBounces,
                           "With --roulette on, the bounce at which a path ends if "
                           "roulette has not ended it (page 15)",
                           1, int(ROULETTE_MAX_DEPTH));
            params.choice("--rough-branches", paths.roughBranches,
                          "Past the camera ray's hit, a rough surface sends both "
                          "branches on (the ray tree) or one, chosen by their shares",
                          {"both", "one"});
            photons.options(params, s);
        },
        .physicalLights = true,
        .adaptShaders = photons.adaptShaders,
        .framePass = [&](const rg::FramePassContext& c) {
            return withPathOptions(
                withCompensation(photons.framePass(c), c, multipleScattering), paths);
        },
    });
}
