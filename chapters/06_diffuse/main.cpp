// Chapter 06 - Diffuse light and shadows (thesis 3.2). The ray generation
// shader adds k_d * I_i * max(0, l.n) for each light a shadow ray reaches;
// shadow rays have their own miss shader and hit groups.
#include <cstdlib>

#include "chapter/rt_chapter.h"

int main(int argc, char** argv) {
    return rg::runRtChapter(argc, argv, {
        .name = "06_diffuse",
        .description = "RayGlass chapter 06: diffuse light with a shadow ray"
                       " to every light",
        .title = "RayGlass 06: diffuse",
        .stage = rg::ReferenceStage::Diffuse,
        .options = [](rg::Params& params, rg::RtChapterSettings& s) {
            rg::Param& epsilon = params.number(
                "--fixed-epsilon", s.epsilon,
                "Experiment: start shadow rays at p + E*n instead of the robust offset"
                " (0: robust)",
                0, 0.1);
            epsilon.logarithmic = true;  // a slider down to 1e-9 and below
            epsilon.check = [](const std::string& v) {  // a distance: finite and > 0
                double e = std::strtod(v.c_str(), nullptr);
                return e > 0 && e < 1e30 ? std::string()
                                         : "must be a positive distance, not " + v;
            };
        },
    });
}
