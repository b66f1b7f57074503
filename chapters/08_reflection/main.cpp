// Chapter 08 - Reflection (thesis 4.1). The ray generation shader bounces
// rays off mirrors in a loop, up to --depth times.
#include "chapter/rt_options.h"

int main(int argc, char** argv) {
    return rg::runRtChapter(argc, argv, {
        .name = "08_reflection",
        .description = "RayGlass chapter 08: mirror reflection, bounces in a loop",
        .title = "RayGlass 08: reflection",
        .stage = rg::ReferenceStage::Reflection,
        .options = [](rg::Params& params, rg::RtChapterSettings& s) {
            rg::addDepthOption(params, s, 5);
        },
    });
}
