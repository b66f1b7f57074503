// Chapter 11 - Rough surfaces (thesis 4.3). A rough surface's reflection is
// the average of --samples rays spread over a lobe around the mirror
// direction; --pattern chooses how the samples are spread. Frames accumulate
// progressively (in a window the overlay changes them live); the default
// pattern continues one Sobol sequence across frames.
#include "rt_options.h"

int main(int argc, char** argv) {
    return rg::runRtChapter(argc, argv, {
        .name = "11_rough",
        .description = "RayGlass chapter 11: rough reflections, sample patterns, progressive accumulation",
        .title = "RayGlass 11: rough surfaces",
        .stage = rg::ReferenceStage::Rough,
        .options = [](rg::Params& params, rg::RtChapterSettings& s) {
            rg::addDepthOption(params, s, 4);
            rg::addFresnelOption(params, s);
            s.samplesPerHit = 25;  // the thesis's figure
            s.pattern = 3;  // sobol
            s.accumulate = true;
            s.referenceSamples = 1024;
            params.integer("--samples", s.samplesPerHit, "Reflection rays per rough hit and frame", 1, 1024);
            params.choice("--pattern", s.pattern, "Sample pattern", {"uniform", "stratified", "hammersley", "sobol"});
            params.toggle("--no-accumulate", s.accumulate, "Every frame on its own (for timing single frames)", true);
            params.integer("--reference-samples", s.referenceSamples,
                           "Samples per rough hit in the CPU reference (a square number)", 4, 65536)
                .live = false;
        },
    });
}
