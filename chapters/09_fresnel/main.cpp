// Chapter 09 - Fresnel (thesis 4.1.1). Dielectrics reflect more at grazing
// angles: Schlick's approximation (--fresnel schlick, schlick-ior) or the
// exact equations (--fresnel exact).
#include "rt_options.h"

int main(int argc, char** argv) {
    return rg::runRtChapter(argc, argv, {
        .name = "09_fresnel",
        .description = "RayGlass chapter 09: Fresnel reflectance, Schlick or exact",
        .title = "RayGlass 09: Fresnel",
        .stage = rg::ReferenceStage::Fresnel,
        .options = [](CLI::App& app, rg::RtChapterSettings& s) {
            rg::addDepthOption(app, s, 5);
            rg::addFresnelOption(app, s);
        },
    });
}
