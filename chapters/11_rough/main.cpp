// Chapter 11 - Rough surfaces (thesis 4.3). A rough surface's reflection is
// the average of --samples rays spread over a lobe around the mirror
// direction; --pattern chooses how the samples are spread. Frames accumulate
// progressively (in a window: P changes the pattern, up/down the samples);
// the default pattern continues one Sobol sequence across frames.
#include "rt_options.h"

#include <map>

int main(int argc, char** argv) {
    return rg::runRtChapter(argc, argv, {
        .name = "11_rough",
        .description = "RayGlass chapter 11: rough reflections, sample patterns, progressive accumulation",
        .title = "RayGlass 11: rough surfaces",
        .stage = rg::ReferenceStage::Rough,
        .options = [](CLI::App& app, rg::RtChapterSettings& s) {
            rg::addDepthOption(app, s, 4);
            rg::addFresnelOption(app, s);
            s.samplesPerHit = 25;  // the thesis's figure
            s.pattern = 3;  // sobol
            s.accumulate = true;
            s.referenceSamples = 1024;
            app.add_option("--samples", s.samplesPerHit, "Reflection rays per rough hit and frame")
                ->check(CLI::Range(1, 1024))
                ->capture_default_str();
            app.add_option("--pattern", s.pattern, "Sample pattern: sobol (default), uniform, stratified or hammersley")
                ->transform(CLI::CheckedTransformer(std::map<std::string, int>{{"uniform", 0}, {"stratified", 1},
                                                                               {"hammersley", 2}, {"sobol", 3}},
                                                    CLI::ignore_case));
            app.add_flag("!--no-accumulate", s.accumulate, "Every frame on its own (for timing single frames)");
            app.add_option("--reference-samples", s.referenceSamples,
                           "Samples per rough hit in the CPU reference (a square number)")
                ->check(CLI::Range(4, 65536))
                ->capture_default_str();
        },
    });
}
