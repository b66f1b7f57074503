// Chapter 15 - Frosted glass. Chapter 11 blurred mirrors the thesis's way
// (4.3), by spreading reflection rays over a cone: no physical material, no
// rough transmission. Here a rough surface is a field of tiny mirror-smooth
// facets (microfacets) whose normals follow the GGX distribution; a ray
// meets one facet, drawn from the normals it can see, and reflects and
// refracts there with chapter 13's exact Fresnel (Walter et al. 2007). The
// light that leaves through glass spreads: frosted glass, and through
// chapter 14's photons, a soft caustic. Roughness 0 is chapter 14 exactly.
#include "chapter/rt_options.h"
#include "photons/photon_pass.h"

int main(int argc, char** argv) {
    // chapter 14's photon pass, its photons through rough surfaces too
    rg::PhotonChapter photons = rg::photonChapter("15_frosted_glass/photon.rgen");
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
                          "chapter 11's cone (page 15's comparison; the reference "
                          "draws visible normals)",
                          {"visible", "cone"});
            photons.options(params, s);
        },
        .physicalLights = true,
        .adaptShaders = photons.adaptShaders,
        .framePass = photons.framePass,
    });
}
