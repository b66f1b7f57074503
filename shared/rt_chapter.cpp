#include "rt_chapter.h"

#include "app.h"
#include "frame_loop.h"
#include "host_device.h"
#include "rt_pipeline.h"
#include "rt_report.h"
#include "rt_scene.h"
#include "scene.h"

#include <algorithm>

namespace rg {

int runRtChapter(int argc, char** argv, const RtChapter& chapter) {
    Options opts;
    RtChapterSettings settings;
    auto extra = [&](CLI::App& app, Options& o) {
        addSceneOptions(app, o, true);
        app.add_option("--sphere-mesh", settings.sphereMesh,
                       "Spheres as icospheres subdivided this often (1-7; 0: analytic, the default)")
            ->check(CLI::Range(0, 7));
        if (chapter.options) chapter.options(app, settings);
    };
    if (auto exit = parseCommandLine(argc, argv, chapter.name, chapter.description, opts, extra)) return *exit;
    return runChapter(opts, [&] {
        Scene scene = toCameraSpace(loadScene(opts.scene.empty() ? defaultScenePath("default") : opts.scene));
        App app;
        initApp(app, opts, chapter.title);
        Image target = createImage2D(app.gpu, app.deletion, opts.width, opts.height, VK_FORMAT_R32G32B32A32_SFLOAT,
                                     VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT);
        RtScene rt = uploadScene(app.gpu, app.deletion, scene, target,
                                 instanceOrder(scene, opts.fileOrder), settings.sphereMesh);

        // [region shaders]
        // SBT: raygen | miss: sky, shadow | hit: quad, sphere, sphere mesh
        // (primary rays), then the same three for shadow rays: no closest hit;
        // the sphere still needs its intersection shader to be found at all.
        RtShaders shaders{
            .raygen = chapter.name + "/raygen.rgen",
            .miss = {"common/sky.rmiss", "common/shadow.rmiss"},
            .hitGroups = {{.closestHit = "common/quad.rchit"},
                          {.closestHit = "common/sphere.rchit", .intersection = "common/sphere.rint"},
                          {.closestHit = "common/mesh_sphere.rchit"},
                          {},
                          {.intersection = "common/sphere.rint"},
                          {}},
        };
        // [end]
        RtPipeline pipeline = createRtPipeline(app.gpu, app.deletion, rt.descriptors.layout, sizeof(gpu::RtPush),
                                               shaders);
        FrameLoop loop(app.gpu, app.window.get(), target, VK_PIPELINE_STAGE_RAY_TRACING_SHADER_BIT_KHR, app.deletion);
        uint32_t firstFrame = 0;  // of the current accumulation
        const char* patterns[] = {"uniform", "stratified", "hammersley", "sobol"};
        FrameTimes times = loop.run(opts.framesToRun(), [&](VkCommandBuffer cmd, uint32_t frame) {
            if (app.window && settings.accumulate) {
                // P: next sample pattern; up/down: twice or half the samples. Both restart the average.
                for (int key : app.window->takeKeys()) {
                    if (key == GLFW_KEY_P) settings.pattern = (settings.pattern + 1) % 4;
                    else if (key == GLFW_KEY_UP) settings.samplesPerHit = std::min(1024, settings.samplesPerHit * 2);
                    else if (key == GLFW_KEY_DOWN) settings.samplesPerHit = std::max(1, settings.samplesPerHit / 2);
                    else continue;
                    firstFrame = frame;
                }
                uint32_t frames = frame - firstFrame + 1;
                app.window->setTitle(chapter.title + " - " + patterns[settings.pattern] + ", " +
                                     std::to_string(settings.samplesPerHit) + " samples/hit x " +
                                     std::to_string(frames) + " frames = " +
                                     std::to_string(frames * settings.samplesPerHit) + " (P, up, down)");
            }
            gpu::RtPush push{
                .frame = frame,
                .maxDepth = uint32_t(settings.maxDepth),
                .samplesPerHit = uint32_t(settings.samplesPerHit),
                .pattern = uint32_t(settings.pattern),
                .fresnelMode = uint32_t(settings.fresnelMode),
                .accumulated = settings.accumulate ? frame - firstFrame : 0,
                .epsilon = settings.epsilon,
            };
            recordTrace(cmd, pipeline, rt.descriptors.set, &push, sizeof(push), rt.width, rt.height);
        });
        ReferenceSettings reference{.stage = chapter.stage, .maxDepth = settings.maxDepth,
                                    .fresnelMode = settings.fresnelMode, .samples = settings.referenceSamples};
        finishRtRun(app, opts, scene, rt, target, times, reference);
    });
}

}  // namespace rg
