#include "chapter/rt_chapter.h"

#include "app/app.h"
#include "app/rt_report.h"
#include "host_device.h"
#include "raytracing/rt_pipeline.h"
#include "raytracing/rt_scene.h"
#include "raytracing/two_launches.h"
#include "scene/scene.h"
#include "viewer/shader_reload.h"
#include "viewer/viewer.h"
#include "vulkan/device_limits.h"
#include "vulkan/frame_loop.h"

#include <CLI/CLI.hpp>

#include <chrono>
#include <cmath>
#include <list>

namespace rg {

int runRtChapter(int argc, char** argv, const RtChapter& chapter) {
    Options opts;
    RtChapterSettings settings;
    Params params;
    if (chapter.options) chapter.options(params, settings);  // the chapter's own first
    params
        .integer("--sphere-mesh", settings.sphereMesh,
                 "Spheres as icospheres subdivided this often (0: analytic spheres)", 0,
                 7)
        .live = false;  // the acceleration structures are built once
    if (chapter.meshes) {  // chapters 12 on; both fixed for the run (no live edit)
        params.choice("--triangles", settings.triangles,
                      "Ray-triangle test: the driver's own, or boxes and Woop, Benthin "
                      "and Wald's watertight test in an intersection shader",
                      {"builtin", "watertight"}).live = false;
        params.choice("--mips", settings.mips,
                      "Textures' mip levels, chosen per hit by ray cones; off: the full "
                      "size only (aliases where a texture is far)",
                      {"on", "off"}).live = false;
    }
    enum { kAuto, kOn, kOff };  // --antialias, as chapter 04
    int antialias = kAuto;
    params.choice("--antialias", antialias,
                  "Average frames of rays through new points in each pixel "
                  "(auto: on in a window, off headless)",
                  {"auto", "on", "off"})
        .section = "view";  // the overlay's View and light section
    params
        .number("--exposure", settings.exposure,
                "Exposure in stops: the image is the light times 2^EV", -10, 10)
        // the overlay's View section, with the camera's and the lights' controls
        .section = "view";
    auto extra = [&](CLI::App& app, Options& o) {
        addSceneOptions(app, o, true);
        params.addTo(app);
    };
    if (auto exit =
            parseCommandLine(argc, argv, chapter.name, chapter.description, opts, extra))
        return *exit;
    // the report says which
    if (antialias == kAuto) antialias = opts.headless ? kOff : kOn;
    return runChapter(opts, [&] {
        auto loadStart = std::chrono::steady_clock::now();
        Scene scene = toCameraSpace(
            loadScene(opts.scene.empty() ? defaultScenePath(chapter.scene) : opts.scene));
        double loadMs = std::chrono::duration<double, std::milli>(
                            std::chrono::steady_clock::now() - loadStart)
                            .count();
        if (!chapter.meshes) refuseMeshes(scene);
        if (chapter.physicalLights) {
            requirePhysicalLights(scene);
            if (opts.reference) refuseSunDiscInReference(scene);
            if (!scene.ambientGiven) scene.ambient = glm::dvec3(0);  // radiometry: none
        } else {
            refusePhysicalLights(scene);
        }
        if (settings.mips == 1) keepLevelZero(scene);  // --mips off
        if (chapter.stage == ReferenceStage::Media) refuseUnstackableMedia(scene);
        App app;
        initApp(app, opts, chapter.title);
        // What grows with the image: the ray counts (4 bytes a pixel) and
        // chapter 10's queue of ray trees (a quarter of the pixels, 128 bytes each).
        double queueBytesPerPixel =
            settings.launches >= 0 ? sizeof(gpu::QueuedTree) / 4.0 : 0.0;
        checkImageFits(
            app.gpu, opts.width, opts.height,
            {.storageBytesPerPixel = 4, .addressedBytesPerPixel = queueBytesPerPixel});
        Image target = createImage2D(
            app.gpu, app.deletion, opts.width, opts.height, VK_FORMAT_R32G32B32A32_SFLOAT,
            VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT);
        TriangleTest triangles = TriangleTest(settings.triangles);
        RtScene rt = uploadScene(app.gpu, app.deletion, scene, target,
                                 {.groupSpheres = opts.groupSpheres,
                                  .fileOrder = opts.fileOrder,
                                  .sphereMeshLevel = settings.sphereMesh,
                                  .triangles = triangles});

        // [region shaders]
        // SBT: raygen | miss: sky, shadow | hit: quad, sphere, mesh (primary
        // rays), then the same three for shadow rays (rt_pipeline.cpp).
        RtShaders shaders{
            .raygen =
                (chapter.raygenFolder.empty() ? chapter.name : chapter.raygenFolder) +
                "/raygen.rgen",
            .miss = {"common/sky.rmiss", "common/shadow.rmiss"},
            .hitGroups = sceneHitGroups(),
        };
        // [end]
        // Chapter 12's --triangles watertight: boxes, and triangle.rint in them.
        useTriangleTest(app.gpu, shaders, triangles);
        // and an any-hit shader where a material is alpha-tested (glTF's MASK)
        bool alphaTest = useAlphaTest(shaders, scene);
        // the ray tree's thin-wall branches only where a material is thin
        bool thinWalls = useThinWalls(shaders, scene);
        // rays carry their cones where a texture has mip levels (chapter 12)
        bool rayCones = useRayCones(shaders, scene);
        // a sun's disc is drawn from only where a sun has one (chapter 14)
        bool sunDiscs = useSunDiscs(shaders, scene);
        // a shading normal of its own only where a mesh brings one (chapter 12)
        bool meshes = useMeshes(shaders, rt);
        if (chapter.adaptShaders) chapter.adaptShaders(shaders, scene);  // chapter 14
        // A run that never averages frames gets a shader without the jitter
        // and the running mean (rt_bindings.glsl's kAverages): a window may
        // switch them on at any time, headless runs only from the start.
        shaders.raygenAverages = app.window || antialias == kOn || settings.accumulate;
        // Branches for huge and tiny numbers only for a scene that has them
        // (chapter 06's page).
        CarefulNumerics careful = carefulNumerics(opts, scene);
        specialize(shaders, careful);
        // --shader-source: that tree's shaders, compiled now (an exercise's
        // starter, docs/index.md), instead of the build's SPIR-V
        std::optional<ShaderReload> source;
        if (!opts.shaderSource.empty()) {
            source.emplace(shaders, opts.shaderSource);
            std::optional<RtShaders> compiled = source->compileNow();
            if (!compiled) throw InputError(opts.shaderSource + ": " + source->status());
            shaders = *compiled;
        }
        RtPipeline pipeline = createRtPipeline(
            app.gpu, app.deletion, rt.descriptors.layout, sizeof(gpu::RtPush), shaders);
        // Chapter 10: two launches, where the driver can size a launch from a
        // GPU buffer (an optional feature).
        bool canTwo = settings.launches >= 0 && app.gpu.physical.traceRaysIndirect;
        if (settings.launches >= 0 && !canTwo)
            std::printf(
                "note: the driver cannot size a launch on the GPU "
                "(rayTracingPipelineTraceRaysIndirect): one launch\n");
        TwoLaunches two =
            canTwo ? createTwoLaunches(app.gpu, app.deletion, rt.descriptors.layout,
                                       shaders, rt.width * rt.height)
                   : TwoLaunches{};
        // Chapter 14's photon map: traced and gathered into a grid before each
        // frame's camera rays.
        std::list<ShaderReload> passSources;  // compile()'s, alive with the pipelines
        auto compile = [&](RtShaders stages) {
            stages.spirvDir.clear();  // the build's
            if (opts.shaderSource.empty()) return stages;
            ShaderReload& tree = passSources.emplace_back(stages, opts.shaderSource);
            std::optional<RtShaders> compiled = tree.compileNow();
            if (!compiled) throw InputError(opts.shaderSource + ": " + tree.status());
            return *compiled;
        };
        FramePass pass = chapter.framePass
                             ? chapter.framePass({app, scene, rt, shaders, compile})
                             : FramePass{};
        FrameLoop loop(app.gpu, app.window.get(), target,
                       VK_PIPELINE_STAGE_RAY_TRACING_SHADER_BIT_KHR, app.deletion);
        // a window's camera, overlay and keys
        Viewer viewer(app, opts, scene, rt, target, loop, params);
        viewer.chapterLine = pass.overlay;  // chapter 14's photons
        // F5, a save
        viewer.reloadShaders(shaders, [&](const RtShaders& compiled,
                                          DeletionQueue& deletion) {
            RtPipeline fresh = createRtPipeline(app.gpu, deletion, rt.descriptors.layout,
                                                sizeof(gpu::RtPush), compiled);
            if (canTwo)
                two = createTwoLaunches(app.gpu, deletion, rt.descriptors.layout,
                                        compiled, rt.width * rt.height);
            pipeline = fresh;
        });
        gpu::RtPush last{};  // the last frame's: what the reference checks
        FrameTimes times = loop.run(opts.framesToRun(), [&](VkCommandBuffer cmd,
                                                            uint32_t frame) {
            // frames since the picture last changed
            uint32_t unchanged = viewer.update(cmd, frame);
            VkExtent2D size = viewer.launchSize();  // smaller while a slow view moves
            bool jitter = antialias != kOff;
            viewer.averaging = jitter || settings.accumulate;
            gpu::RtPush push{
                .frame = frame,
                .maxDepth = uint32_t(settings.maxDepth),
                .samplesPerHit = uint32_t(settings.samplesPerHit),
                .pattern = uint32_t(settings.pattern),
                .fresnelMode = uint32_t(settings.fresnelMode),
                .accumulated = viewer.averaging ? unchanged : 0,
                .epsilon = settings.epsilon,
                .wavelength = settings.wavelength,
                .exposure = std::exp2(settings.exposure),
                .antialias = jitter,
                .facetSampling = uint32_t(settings.facetSampling),
                .maxPathDepth = uint32_t(settings.maxDepth),  // no roulette
            };
            if (pass.record)
                pass.record(cmd, push, {push.accumulated, viewer.viewOnlyChanged()});
            last = push;
            if (canTwo)
                recordLaunches(cmd, two, pipeline, rt.descriptors.set, push, size.width,
                               size.height, Launches(settings.launches), frame);
            else
                recordTrace(cmd, pipeline, rt.descriptors.set, &push, sizeof(push),
                            size.width, size.height);
            if (pass.after) pass.after(cmd, push, shaders.raygenAverages);
        });
        // closed while moving: the PNG, the report and --reference get a full frame
        if (viewer.previewed()) {
            last.accumulated = 0;
            last.gatherDefer = 0;  // chapter 14: every cell in place, no pass after
            submitOnce(app.gpu, [&](VkCommandBuffer cmd) {
                memoryBarrier(cmd,
                              VK_PIPELINE_STAGE_RAY_TRACING_SHADER_BIT_KHR |
                                  VK_PIPELINE_STAGE_TRANSFER_BIT,
                              VK_ACCESS_SHADER_WRITE_BIT | VK_ACCESS_TRANSFER_WRITE_BIT,
                              VK_PIPELINE_STAGE_RAY_TRACING_SHADER_BIT_KHR,
                              VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT);
                recordTrace(cmd, pipeline, rt.descriptors.set, &last, sizeof(last),
                            rt.width, rt.height);
            });
        }
        ReferenceSettings reference{.stage = chapter.stage,
                                    .maxDepth = settings.maxDepth,
                                    .fresnelMode = settings.fresnelMode,
                                    .samples = settings.referenceSamples,
                                    .wavelength = settings.wavelength,
                                    .frames = last.accumulated + 1,
                                    .firstFrame = last.frame - last.accumulated,
                                    .exposure = last.exposure,
                                    .antialias = last.antialias != 0};
        if (pass.reference) pass.reference(reference);
        // the last frame's launches
        nlohmann::json extra = {{"launches", two.lastLaunches}, {"scene_load_ms", loadMs},
                                {"parameters", params.values()},
                                {"numerics", toJson(careful)},
                                {"alpha_test", alphaTest},
                                {"thin_walls", thinWalls},
                                {"ray_cones", rayCones},
                                {"sun_discs", sunDiscs},
                                {"shading_normals", meshes}};
        if (pass.finish) extra.update(pass.finish());
        if (canTwo)
            extra["trees_past_first_hit"] = {{"trees", lastTrees(two)},
                                             {"pixels", rt.width * rt.height},
                                             {"queue_capacity", two.capacity}};
        finishRtRun(app, opts, scene, rt, target, times, reference, extra);
    });
}

}  // namespace rg
