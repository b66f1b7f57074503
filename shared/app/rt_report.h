// The end of every ray tracing chapter's run: read the image back, write the
// PNG (and the linear PFM beside it), count the rays, compare with the CPU
// reference when --reference asks, and write the report.
#pragma once
#include "app/app.h"
#include "app/report.h"
#include "raytracing/rt_scene.h"
#include "reference/reference.h"

namespace rg {

// Rays per frame over milliseconds per frame, in millions per second (0 without a time).
inline double mraysPerSecond(uint64_t rays, double ms) {
    return ms > 0 ? double(rays) / (ms * 1e-3) / 1e6 : 0.0;
}

// `extra`: the chapter's own fields, added to the report (chapter 10: its launches).
nlohmann::json finishRtRun(const App& app, const Options& opts, const Scene& scene,
                           const RtScene& rt, const Image& target,
                           const FrameTimes& times,
                           const ReferenceSettings& referenceSettings,
                           const nlohmann::json& extra = nlohmann::json::object());

}  // namespace rg
