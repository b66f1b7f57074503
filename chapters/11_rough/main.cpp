// Chapter 11 - Rough surfaces (thesis 4.3). A rough surface's reflection is
// the average of --samples rays spread over a lobe around the mirror
// direction; --pattern chooses how the samples are spread. Frames accumulate
// progressively (in a window the overlay changes them live); the default
// pattern continues one Sobol sequence across frames.
#include "chapter/rt_options.h"

int main(int argc, char** argv) {
    return rg::runRtChapter(argc, argv, {
        .name = "11_rough",
        .description = "RayGlass chapter 11: rough reflections, sample patterns,"
                       " progressive accumulation",
        .title = "RayGlass 11: rough surfaces",
        .stage = rg::ReferenceStage::Rough,
        .options = [](rg::Params& params, rg::RtChapterSettings& s) {
            rg::addDepthOption(params, s, 4);
            rg::addFresnelOption(params, s);
            rg::addRoughOptions(params, s);
        },
    });
}
