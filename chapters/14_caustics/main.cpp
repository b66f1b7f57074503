// Chapter 14 - Light through glass (past the thesis, toward its task:
// "compare with similar objects in the real world"). Until now a shadow ray
// that meets glass says "dark": every glass casts a black shadow, where a
// real one focuses sunlight into a caustic. Eye rays cannot find that light:
// the path sun -> glass -> floor -> eye reaches the floor from the one
// direction the glass bends the sun into, which no ray from a diffuse point
// picks out. So light is traced from the lights instead (photon mapping,
// Jensen 1996): each frame a launch sends photons at the glasses and
// mirrors, follows them through reflection and refraction, and stores where
// they land on diffuse surfaces; compute shaders sort them into a hash
// grid; and the camera rays' diffuse hits add the photons' power within a
// radius that shrinks frame by frame (Knaus and Zwicker 2011), so the
// average converges to the right light. Lights are now in watts.
#include "chapter/rt_options.h"
#include "photons/photon_pass.h"

int main(int argc, char** argv) {
    // The photon pass (shared/photons/): its options, --caustics transmit's
    // shaders, and the photon map traced before each frame's camera rays.
    rg::PhotonChapter photons = rg::photonChapter("14_caustics/photon.rgen");
    return rg::runRtChapter(argc, argv, {
        .name = "14_caustics",
        .description = "RayGlass chapter 14: light through glass, caustics and coloured "
                       "shadows by photon mapping",
        .title = "RayGlass 14: caustics",
        .stage = rg::ReferenceStage::Caustics,
        .meshes = true,
        // A clear and an amber glass ball on a floor in low sunlight.
        .scene = "caustics",
        .options = [&](rg::Params& params, rg::RtChapterSettings& s) {
            rg::addDepthOption(params, s, 8);
            s.fresnelMode = 2;  // exact, as chapter 13
            rg::addSpectralOptions(params, s);
            photons.options(params, s);
        },
        .physicalLights = true,  // watts, and no ambient light unless the scene gives it
        .adaptShaders = photons.adaptShaders,  // --caustics transmit's any-hit shaders
        .framePass = photons.framePass,  // photons traced and sorted before each frame
    });
}
