// Parameters that several ray tracing chapters share, declared once for the
// command line and the overlay (params.h).
#pragma once
#include "chapter/rt_chapter.h"
#include "core/params.h"

#include <cstdlib>
#include <string>

namespace rg {

// --depth: how many times a ray may bounce (reflect or refract), 0 to 8.
inline void addDepthOption(Params& params, RtChapterSettings& s, int defaultDepth) {
    s.maxDepth = defaultDepth;
    params.integer("--depth", s.maxDepth,
                   "Bounce limit (reflections and refractions per path)", 0, 8);
}

// --fresnel: schlick (the material's f0, the thesis's 0.08), schlick-ior
// (f0 from the index of refraction), exact (the Fresnel equations).
inline void addFresnelOption(Params& params, RtChapterSettings& s) {
    params.choice("--fresnel", s.fresnelMode, "Fresnel reflectance",
                  {"schlick", "schlick-ior", "exact"});
}

// --launches: chapter 10 traces the ray trees that go on past the first hit
// in a second launch (two), in the same launch (one), or chooses each frame
// from how many pixels have such a tree (auto).
inline void addLaunchesOption(Params& params, RtChapterSettings& s) {
    s.launches = 0;
    params.choice("--launches", s.launches,
                  "Ray trees past the first hit: in a second launch (two), in the first "
                  "(one), or chosen per frame",
                  {"auto", "one", "two"});
}

// Chapter 11's rough reflections and progressive accumulation (chapter 12
// keeps them): --samples, --pattern, --no-accumulate, --reference-samples.
inline void addRoughOptions(Params& params, RtChapterSettings& s) {
    s.samplesPerHit = 25;  // the thesis's figure
    s.pattern = 3;  // sobol
    s.accumulate = true;
    s.referenceSamples = 1024;
    params.integer("--samples", s.samplesPerHit,
                   "Reflection rays per rough hit and frame", 1, 1024);
    params.choice("--pattern", s.pattern, "Sample pattern",
                  {"uniform", "stratified", "hammersley", "sobol"});
    params.toggle("--no-accumulate", s.accumulate,
                  "Every frame on its own (for timing single frames)", true);
    params
        .integer("--reference-samples", s.referenceSamples,
                 "Samples per rough hit in the CPU reference (a square number)", 4, 65536)
        .live = false;
}

// Chapter 13's dispersion: --wavelength (one wavelength for every path, to
// see or measure it alone) and progressive accumulation, as chapter 11's.
inline void addSpectralOptions(Params& params, RtChapterSettings& s) {
    s.accumulate = true;
    params
        .number("--wavelength", s.wavelength,
                "Trace every path at this wavelength in nm, 380-780 (0: all, one per "
                "path and frame)",
                0, 780)
        .check = [](const std::string& v) {
        double nm = std::strtod(v.c_str(), nullptr);
        return nm == 0 || (nm >= 380 && nm <= 780) ? std::string()
                                                   : "must be 0 or 380-780 nm, not " + v;
    };
    params.toggle("--no-accumulate", s.accumulate,
                  "Every frame on its own (for timing single frames)", true);
}

}  // namespace rg
