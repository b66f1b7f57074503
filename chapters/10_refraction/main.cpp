// Chapter 10 - Refraction (thesis 4.2). Glass splits each ray into a
// reflected and a refracted branch (Snell's law, Fresnel weights, total
// internal reflection); the ray generation shader follows both, and the
// trees that go on past the first hit get a launch of their own.
#include "chapter/rt_options.h"

int main(int argc, char** argv) {
    return rg::runRtChapter(argc, argv, {
        .name = "10_refraction",
        .description = "RayGlass chapter 10: refraction through glass, the full ray tree",
        .title = "RayGlass 10: refraction",
        .stage = rg::ReferenceStage::Refraction,
        .options = [](rg::Params& params, rg::RtChapterSettings& s) {
            rg::addDepthOption(params, s, 6);
            rg::addFresnelOption(params, s);
            rg::addLaunchesOption(params, s);
        },
    });
}
