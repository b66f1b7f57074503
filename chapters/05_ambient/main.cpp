// Chapter 05 - Ambient light (thesis 3.1). Only the ray generation shader
// changes (shaders/05_ambient/raygen.rgen): a hit is k_a * I_a.
#include "chapter/rt_chapter.h"

int main(int argc, char** argv) {
    return rg::runRtChapter(argc, argv, {
        .name = "05_ambient",
        .description = "RayGlass chapter 05: ambient light, I = ka * Ia",
        .title = "RayGlass 05: ambient",
        .stage = rg::ReferenceStage::Ambient,
    });
}
