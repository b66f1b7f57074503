// Chapter 07 - Specular light (thesis 3.3). The ray generation shader adds
// Blinn-Phong's k_s * I_i * max(0, n.h)^shininess.
#include "chapter/rt_chapter.h"

int main(int argc, char** argv) {
    return rg::runRtChapter(argc, argv, {
        .name = "07_specular",
        .description = "RayGlass chapter 07: Blinn-Phong specular light",
        .title = "RayGlass 07: specular",
        .stage = rg::ReferenceStage::Specular,
    });
}
