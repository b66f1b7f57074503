// What a chapter writes: the rendered image (PNG through the display
// transform, PFM with the raw linear floats) and the JSON report.
#pragma once
#include "cli.h"
#include "context.h"
#include "resources.h"

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace rg {

// Linear RGBA float pixels, top row first.
struct FloatImage {
    uint32_t width = 0, height = 0;
    std::vector<float> rgba;
};

// Copies an RGBA32F image in GENERAL layout to the host. Waits for the GPU.
FloatImage readImage(const Gpu& gpu, const Image& image, VkPipelineStageFlags lastWriter);

void writePng(const std::string& path, const FloatImage& image);
void writePfm(const std::string& path, const FloatImage& image);  // lossless, linear
FloatImage readPfm(const std::string& path);

// Per-frame measurements of a run.
struct FrameTimes {
    std::vector<double> gpuMs;  // timestamp queries around the chapter's work
    std::vector<double> cpuMs;  // wall clock of each frame on the host
};

// The report's common fields: chapter, device, driver, width, height, frames,
// gpu_ms {median,min,max}, cpu_ms, validation_messages. Chapters add theirs.
nlohmann::json makeReport(const Options& opts, const Gpu& gpu, const FrameTimes& times);
void writeReport(const std::string& path, const nlohmann::json& report);

double median(std::vector<double> values);

}  // namespace rg
