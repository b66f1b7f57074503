// The JSON report every chapter writes beside its image (chapter 01 on): the
// run's device, size and times; chapters add their own fields.
#pragma once
#include "core/cli.h"
#include "vulkan/context.h"
#include "vulkan/gpu_timer.h"

#include <nlohmann/json.hpp>

#include <string>

namespace rg {

// The report's common fields: chapter, device, driver, width, height, frames,
// gpu_ms {median,min,max}, cpu_ms, validation_messages. Chapters add theirs.
nlohmann::json makeReport(const Options& opts, const Gpu& gpu, const FrameTimes& times);
void writeReport(const std::string& path, const nlohmann::json& report);

}  // namespace rg
