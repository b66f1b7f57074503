// Command-line options that several ray tracing chapters share.
#pragma once
#include "rt_chapter.h"

#include <map>

namespace rg {

// --depth: how many times a ray may bounce (reflect or refract), 0 to 8.
inline void addDepthOption(CLI::App& app, RtChapterSettings& s, int defaultDepth) {
    s.maxDepth = defaultDepth;
    app.add_option("--depth", s.maxDepth, "Bounce limit (reflections and refractions per path)")
        ->check(CLI::Range(0, 8))
        ->capture_default_str();
}

// --fresnel: schlick (the material's f0, the thesis's 0.08), schlick-ior
// (f0 from the index of refraction), exact (the Fresnel equations).
inline void addFresnelOption(CLI::App& app, RtChapterSettings& s) {
    app.add_option("--fresnel", s.fresnelMode, "Fresnel reflectance: schlick, schlick-ior or exact")
        ->transform(CLI::CheckedTransformer(std::map<std::string, int>{{"schlick", 0}, {"schlick-ior", 1}, {"exact", 2}},
                                            CLI::ignore_case));
}

}  // namespace rg
