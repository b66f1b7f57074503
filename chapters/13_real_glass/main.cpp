// Chapter 13 - Real glass (past the thesis, toward its task: "compare with
// similar objects in the real world"). Chapter 10 puts air outside every
// glass. Here each branch of the ray tree carries the media it is inside,
// with priorities where media overlap, so water meets glass at 1.333 / 1.5
// and a bubble in glass is air; and a medium absorbs along the way
// (Beer-Lambert), so a glass's colour depends on its thickness; and its
// index depends on the wavelength (dispersion): paths carry one wavelength
// each, and frames accumulate into the colour. The Fresnel equations are
// exact by default: Schlick's f0 is for air only.
#include "chapter/rt_options.h"

int main(int argc, char** argv) {
    return rg::runRtChapter(argc, argv, {
        .name = "13_real_glass",
        .description = "RayGlass chapter 13: real glass, nested media, absorption"
                       " and dispersion",
        .title = "RayGlass 13: real glass",
        .stage = rg::ReferenceStage::Media,
        .meshes = true,
        // A glass of water with ice, a bubble in glass, coloured glass.
        .scene = "real_glass",
        .options = [](rg::Params& params, rg::RtChapterSettings& s) {
            rg::addDepthOption(params, s, 8);
            s.fresnelMode = 2;  // exact: between two media Schlick's f0 would be wrong
            rg::addFresnelOption(params, s);
            rg::addSpectralOptions(params, s);
        },
    });
}
