#include "app/report.h"

#include "core/files.h"
#include "core/interrupt.h"

namespace rg {

namespace {
nlohmann::json stats(const std::vector<double>& v) {
    if (v.empty()) return {{"median", nullptr}, {"min", nullptr}, {"max", nullptr}};
    return {{"median", median(v)},
            {"min", *std::min_element(v.begin(), v.end())},
            {"max", *std::max_element(v.begin(), v.end())}};
}
}  // namespace

nlohmann::json makeReport(const Options& opts, const Gpu& gpu, const FrameTimes& times) {
    nlohmann::json report = {
        {"chapter", opts.chapter},
        {"device", gpu.physical.properties.deviceName},
        {"driver", gpu.physical.driver},
        {"width", opts.width},
        {"height", opts.height},
        {"frames", times.gpuMs.size()},
        {"headless", opts.headless},
        {"gpu_ms", stats(times.gpuMs)},
        {"cpu_ms", stats(times.cpuMs)},
        {"validation", opts.validation},
        {"validation_messages", validationMessageCount().load()},
    };
    if (interrupted()) {  // Ctrl-C: the frames done so far (interrupt.h)
        std::string requested =
            opts.framesToRun() > 0 ? std::to_string(opts.framesToRun()) : "unlimited";
        report["interrupted"] = {{"signal", interruptSignalName()},
                                 {"frames_done", times.gpuMs.size()},
                                 {"frames_requested", requested}};
        setInterruptedRunSummary("after " + std::to_string(times.gpuMs.size()) + " of " +
                                 requested + " frames; the outputs hold the frames done");
    }
    return report;
}

void writeReport(const std::string& path, const nlohmann::json& report) {
    std::string text = report.dump(2) + "\n";
    writeFileAtomically(path, text.data(), text.size());
}

}  // namespace rg
