#include "app/rt_report.h"

#include "core/interrupt.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>

namespace rg {

namespace {
// --reference: the CPU reference at the same size, its error images and the
// error in the report. A reference cut short by Ctrl-C is no reference: then
// nothing of it is written.
void compareWithReference(nlohmann::json& report, const Scene& scene,
                          const ReferenceSettings& settings, const FloatImage& image,
                          const std::string& output) {
    auto start = std::chrono::steady_clock::now();
    ReferenceRenderer reference(scene);
    FloatImage expected = reference.render(settings, image.width, image.height);
    if (interrupted()) return;
    double cpuMs = std::chrono::duration<double, std::milli>(
                       std::chrono::steady_clock::now() - start)
                       .count();
    FloatImage heat;
    ImageError e = compareImages(image, expected, &heat);
    std::filesystem::path png(output);
    std::string stem = (png.parent_path() / png.stem()).string();
    writePng(stem + "_reference.png", expected);
    writePfm(stem + "_reference.pfm", expected);
    writePng(stem + "_error.png", heat);
    report["error"] = {{"rmse", e.rmse},
                       {"max_abs", e.maxAbs},
                       {"frac_over_1_255", e.fracOver1_255},
                       {"psnr_db", e.psnrDb},
                       {"non_finite_pixels", e.nonFinite},
                       {"reference_cpu_ms", cpuMs},
                       {"heat_map", stem + "_error.png"}};
    if (settings.stage == ReferenceStage::Rough) {  // the reference's own error
        double sumSq = 0;
        for (size_t i = 3; i < expected.rgba.size(); i += 4)
            sumSq += double(expected.rgba[i]) * expected.rgba[i];
        double rms = std::sqrt(sumSq / double(expected.rgba.size() / 4));
        report["error"]["reference_samples"] = settings.samples;
        report["error"]["reference_std_error_rms"] = rms;
        std::printf(
            "reference: %d samples per rough hit, its own standard error (RMS over "
            "pixels) %.2e\n",
            settings.samples, rms);
    }
    std::printf(
        "vs CPU reference: rmse %.2e, max %.2e, %.4f%% of pixels off by > 1/255, PSNR "
        "%.1f dB\n",
        e.rmse, e.maxAbs, 100 * e.fracOver1_255, e.psnrDb);
}
}  // namespace

nlohmann::json finishRtRun(const App& app, const Options& opts, const Scene& scene,
                           const RtScene& rt, const Image& target,
                           const FrameTimes& times,
                           const ReferenceSettings& referenceSettings,
                           const nlohmann::json& extra) {
    // stopped before the first frame: nothing to write
    if (interrupted() && times.gpuMs.empty()) return {};
    FloatImage image =
        readImage(app.gpu, target, VK_PIPELINE_STAGE_RAY_TRACING_SHADER_BIT_KHR);
    std::filesystem::path png(opts.output);
    writePng(opts.output, image);
    writePfm(std::filesystem::path(png).replace_extension(".pfm").string(), image);

    nlohmann::json report = makeReport(opts, app.gpu, times);
    report["scene"] = scene.path;
    // a window's last view, to render again
    report["camera"] = cameraToJson(scene.camera, scene.origin);
    // counted by the ray generation shader, last frame
    uint64_t rays = countRays(app.gpu, rt);
    double medianMs = median(times.gpuMs);
    report["rays_per_frame"] = rays;
    report["mrays_per_s"] = mraysPerSecond(rays, medianMs);
    uint64_t nonFinite = 0;
    for (float v : image.rgba) nonFinite += !std::isfinite(v);
    report["non_finite_values"] = nonFinite;
    nlohmann::json& accel = report["acceleration"];
    accel["layout"] = rt.group.objects.empty() ? "instances" : "grouped";
    accel["tlas_instances"] = rt.tlas.count;
    accel["tlas_build_ms"] = rt.tlas.buildMs;
    VkDeviceSize blasBytes = rt.group.stats.compactBytes;
    double blasMs = rt.group.stats.buildMs + rt.group.stats.compactMs;
    for (const BlasStats& s : rt.shapes.stats) {
        blasBytes += s.compactBytes;
        blasMs += s.buildMs + s.compactMs;
    }
    accel["blas_bytes"] = blasBytes;  // compacted
    accel["blas_build_ms"] = blasMs;
    accel["tlas_bytes"] = rt.tlas.buildBytes;
    // Chapter 12: each mesh's one BLAS, and how many objects place it.
    std::vector<size_t> placed(scene.meshes.size(), 0);
    for (const Object& o : scene.objects)
        if (o.type == ShapeType::Mesh) ++placed[o.mesh];
    nlohmann::json meshes = nlohmann::json::array();
    for (size_t k = 0; k < scene.meshes.size(); ++k) {
        const Mesh& m = *scene.meshes[k];
        // after the unit quad and sphere
        const BlasStats& stats = rt.shapes.stats[2 + k];
        meshes.push_back({{"name", m.name},
                          {"triangles", m.indices.size() / 3},
                          {"vertices", m.vertices.size()},
                          {"open_edges", m.openEdges},
                          {"degenerate_dropped", m.degenerate},
                          {"instances", placed[k]},
                          {"blas_bytes", stats.compactBytes},
                          {"blas_build_ms", stats.buildMs + stats.compactMs},
                          {"buffer_bytes", m.vertices.size() * sizeof(glm::vec3) *
                                                   (m.normals.empty() ? 1 : 2) +
                                               m.indices.size() * sizeof(uint32_t)}});
    }
    if (!meshes.empty()) accel["meshes"] = meshes;
    // Chapter 12: the meshes' textures, one image each with its mip levels
    // (rt_textures.h); texels: level 0's, bytes: every level's
    if (!scene.textures.empty())
        report["textures"] = {{"count", scene.textures.size()},
                              {"texels", rt.textures.texels},
                              {"levels", rt.textures.levels},
                              {"bytes", rt.textures.bytes},
                              {"bytes_per_texel", double(rt.textures.bytes) /
                                                      double(rt.textures.texels)}};
    std::printf("GPU median %.3f ms over %zu frames, %llu rays per frame, %.1f Mrays/s\n",
                medianMs, times.gpuMs.size(), (unsigned long long)rays,
                report["mrays_per_s"].get<double>());

    if (opts.reference && !interrupted())
        compareWithReference(report, scene, referenceSettings, image, opts.output);
    report.update(extra);
    report["validation_messages"] = validationMessageCount().load();
    writeReport(opts.report, report);
    std::printf("Wrote %s and %s\n", opts.output.c_str(), opts.report.c_str());
    return report;
}

}  // namespace rg
