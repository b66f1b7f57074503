// Chapter 09 - Fresnel (thesis 4.1.1). Dielectrics reflect more at grazing
// angles: Schlick's approximation (--fresnel schlick, schlick-ior) or the
// exact equations (--fresnel exact).
#include "chapter/rt_options.h"
#include "reference/reference.h"

#include <cmath>
#include <cstdio>

namespace {

// [region schlick_table]
// How far Schlick's approximation is from the exact reflectance of glass
// (n = 1.517, from air), over the angle of incidence.
void printSchlickError() {
    const double n = 1.517, pi = 3.14159265358979323846;
    std::printf("angle  exact    schlick(f0=%.4f)  error    schlick(f0=0.08)  error\n",
                std::pow(0.517 / 2.517, 2));
    for (int degrees = 0; degrees <= 90; degrees += degrees < 80 ? 10 : 3) {
        double c = std::cos(degrees * pi / 180);
        double exact = rg::referenceFresnel(2, 0, c, 1, n);
        double fromIor = rg::referenceFresnel(1, 0, c, 1, n);
        double thesis = rg::referenceFresnel(0, 0.08, c, 1, n);
        std::printf("%5d  %.5f  %.5f           %+.5f  %.5f           %+.5f\n", degrees,
                    exact, fromIor, fromIor - exact, thesis, thesis - exact);
    }
}
// [end]

}  // namespace

int main(int argc, char** argv) {
    printSchlickError();
    return rg::runRtChapter(argc, argv, {
        .name = "09_fresnel",
        .description = "RayGlass chapter 09: Fresnel reflectance, Schlick or exact",
        .title = "RayGlass 09: Fresnel",
        .stage = rg::ReferenceStage::Fresnel,
        .options = [](rg::Params& params, rg::RtChapterSettings& s) {
            rg::addDepthOption(params, s, 5);
            rg::addFresnelOption(params, s);
        },
    });
}
