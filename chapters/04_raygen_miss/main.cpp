// Chapter 04 - Ray generation and miss (thesis 2.2.2-2.2.3).
// The first rays: a ray tracing pipeline (ray generation, miss, closest-hit
// and the sphere's intersection shader), its shader binding table, and one
// camera ray per pixel through chapter 03's acceleration structures. A hit
// shows the surface normal; a miss shows the sky image. --reference renders
// the same picture on the CPU in double precision and reports the error.
#include "app/app.h"
#include "app/rt_report.h"
#include "host_device.h"
#include "raytracing/rt_pipeline.h"
#include "raytracing/rt_scene.h"
#include "scene/scene.h"
#include "viewer/viewer.h"
#include "vulkan/frame_loop.h"

#include <CLI/CLI.hpp>

int main(int argc, char** argv) {
    rg::Options opts;
    // [region antialias_option]
    // Antialiasing (this chapter's last section): on in a window, where the
    // frames average while the view rests; headless only when asked, so that
    // a plain run traces each pixel's centre, as the chapters before did.
    rg::Params params;
    enum { kAuto, kOn, kOff };
    int antialias = kAuto;
    params.choice("--antialias", antialias,
                  "Average frames of rays through new points in each pixel "
                  "(auto: on in a window, off headless)",
                  {"auto", "on", "off"})
        .section = "view";  // the overlay's View and light section
    // [end]
    auto extra = [&](CLI::App& app, rg::Options& o) {
        rg::addSceneOptions(app, o, true);
        params.addTo(app);
    };
    if (auto exit = rg::parseCommandLine(
            argc, argv, "04_raygen_miss",
            "RayGlass chapter 04: ray generation, miss, the SBT", opts, extra))
        return *exit;
    // the report says which
    if (antialias == kAuto) antialias = opts.headless ? kOff : kOn;
    return rg::runChapter(opts, [&] {
        // Moved so the camera is at the origin, in double, before any float is
        // made: precision anywhere in the world (chapter 06's page).
        rg::Scene scene = rg::toCameraSpace(rg::loadScene(
            opts.scene.empty() ? rg::defaultScenePath("default") : opts.scene));
        rg::refuseMeshes(scene);  // spheres and quads only, until chapter 12
        rg::refusePhysicalLights(scene);  // the thesis's lights, until chapter 14
        rg::App app;
        rg::initApp(app, opts, "RayGlass 04: ray generation and miss");
        rg::Image target = rg::createImage2D(
            app.gpu, app.deletion, opts.width, opts.height, VK_FORMAT_R32G32B32A32_SFLOAT,
            VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT);
        // Chapter 03's structures, plus the buffers the shaders read.
        rg::RtScene rt = rg::uploadScene(
            app.gpu, app.deletion, scene, target,
            {.groupSpheres = opts.groupSpheres, .fileOrder = opts.fileOrder});

        // [region shaders]
        // The SBT's records, in order: raygen | miss 0 | hit 0 (quads), hit 1 (spheres).
        rg::RtShaders shaders{
            .raygen = "04_raygen_miss/raygen.rgen",
            .miss = {"common/sky.rmiss"},
            // Hit group 0: triangles; 1: procedural spheres.
            .hitGroups = {{.closestHit = "common/quad.rchit"},
                          {.closestHit = "common/sphere.rchit",
                           .intersection = "common/sphere.rint"}},
        };
        // The sphere test's branches for huge and tiny sizes only where the
        // scene has them (kCarefulSizes; chapter 06's page).
        rg::CarefulNumerics careful = rg::carefulNumerics(opts, scene);
        rg::specialize(shaders, careful);
        rg::RtPipeline pipeline =
            rg::createRtPipeline(app.gpu, app.deletion, rt.descriptors.layout,
                                 sizeof(rg::gpu::RtPush), shaders);
        // [end]

        rg::FrameLoop loop(app.gpu, app.window.get(), target,
                           VK_PIPELINE_STAGE_RAY_TRACING_SHADER_BIT_KHR, app.deletion);
        // [region viewer]
        // In a window: a camera to fly, an overlay with timings, a target that
        // follows the window's size (shared/viewer/viewer.h). Headless: nothing.
        rg::Viewer viewer(app, opts, scene, rt, target, loop, params);
        // Saving a shader (or F5) compiles it again: then the pipeline from it.
        viewer.reloadShaders(
            shaders, [&](const rg::RtShaders& compiled, rg::DeletionQueue& deletion) {
                pipeline = rg::createRtPipeline(app.gpu, deletion, rt.descriptors.layout,
                                                sizeof(rg::gpu::RtPush), compiled);
            });
        rg::gpu::RtPush last{};  // the last frame's: what the reference checks
        rg::FrameTimes times = loop.run(opts.framesToRun(), [&](VkCommandBuffer cmd,
                                                                uint32_t frame) {
            // Records the camera's upload when it moved; returns how many
            // frames ago the picture last changed (headless: `frame`).
            uint32_t unchanged = viewer.update(cmd, frame);
            // the overlay may choose "auto": on in a window
            bool jitter = antialias != kOff;
            viewer.averaging = jitter;
            rg::gpu::RtPush push{.frame = frame,
                                 // 0: the picture starts again
                                 .accumulated = jitter ? unchanged : 0,
                                 .antialias = jitter};
            rg::recordTrace(cmd, pipeline, rt.descriptors.set, &push, sizeof(push),
                            rt.width, rt.height);
            last = push;
        });
        // [end]
        // The reference integrates over the same points of each pixel.
        rg::ReferenceSettings reference{.stage = rg::ReferenceStage::Normals,
                                        .frames = last.accumulated + 1,
                                        .antialias = last.antialias != 0};
        rg::finishRtRun(app, opts, scene, rt, target, times, reference,
                        {{"parameters", params.values()},
                         {"numerics", rg::toJson(careful)}});
    });
}
