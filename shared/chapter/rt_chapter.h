// Chapters 05-11 change only their shaders (and the reference's stage): this
// is chapter 04's main() for them, with the shadow ray type added to the SBT.
#pragma once
#include "core/cli.h"
#include "core/params.h"
#include "host_device.h"
#include "reference/reference.h"

#include <vulkan/vulkan.h>

#include <functional>
#include <string>

namespace rg {

struct RtChapterSettings {
    int maxDepth = 1;
    int samplesPerHit = 1;
    int pattern = 0;
    int facetSampling = 0;  // chapter 15's --sampling: FACETS_VISIBLE, FACETS_CONE
    int fresnelMode = 0;
    // > 0: a fixed offset for secondary rays (chapter 06's experiment)
    float epsilon = 0;
    bool accumulate = false;   // chapter 11: average frames progressively
    // chapter 11: samples per rough hit in the converged CPU reference
    int referenceSamples = 0;
    // > 0: spheres as icospheres of this subdivision level (performance.md)
    int sphereMesh = 0;
    // chapter 13: >= 380, every path at this wavelength (nm); else one drawn per path
    float wavelength = 0;
    // chapter 10's --launches: 0 auto, 1 one, 2 two (two_launches.h); -1: one, no choice
    int launches = -1;
    // --exposure, in stops: the image is the radiance times 2^exposure
    float exposure = 0;
    // chapter 12 on, --triangles: 0 the driver's triangle test, 1 watertight (accel.h)
    int triangles = 0;
    // chapter 12 on, --mips: 0 on (ray cones choose a level), 1 off (level 0)
    int mips = 0;
};

struct App;
struct RtScene;
struct RtShaders;

// Chapter 14 on: a pass of the chapter's own recorded before each frame's
// camera rays (the photon map), made once the scene is on the GPU.
// What changed for a frame, as a FramePass needs to know it.
struct FrameChange {
    uint32_t accumulated;  // frames already averaged into the picture
    bool viewOnly;         // only the view changed (a window's camera): not the light
};
struct FramePass {
    // Records the pass for a frame; it may fill the push constants' fields
    // the camera rays read (the photon map's address, the radius).
    std::function<void(VkCommandBuffer cmd, gpu::RtPush& push, FrameChange change)>
        record;
    // Records what follows the frame's camera rays, given their push
    // constants and whether they average frames (chapter 14's deferred
    // gathers add their light to the picture).
    std::function<void(VkCommandBuffer cmd, const gpu::RtPush& push, bool averages)>
        after;
    // After the last frame: writes what the pass keeps (chapter 14's
    // --photons-ply) and returns its part of the run's report.
    std::function<nlohmann::json()> finish;
    // A line for the window's overlay, given the frames' GPU ms (chapter
    // 14: photons per second and the radius).
    std::function<std::string(double gpuMs)> overlay;
    // What the CPU reference needs to know of the pass (chapter 14: the
    // frames' radii), given its settings for the frames rendered.
    std::function<void(ReferenceSettings&)> reference;
};
struct FramePassContext {
    App& app;
    const Scene& scene;
    const RtScene& rt;
    const RtShaders& shaders;  // the camera rays' (specialized as theirs)
    // A pass's own stages as the camera's came: the build's SPIR-V, or
    // compiled now from --shader-source's tree (an exercise's copy).
    std::function<RtShaders(RtShaders)> compile;
};

struct RtChapter {
    std::string name;         // "05_ambient": the executable, its shader folder
    std::string description;  // for --help
    std::string title;        // the window's title
    ReferenceStage stage;     // what the CPU reference renders
    // the ray generation shader's folder if not `name`'s (chapter 12 uses 11's)
    std::string raygenFolder;
    bool meshes = false;      // chapter 12 on: scenes may hold triangle meshes
    // the scene without --scene: bin/assets/scenes/<scene>.json
    std::string scene = "default";
    // Declares the chapter's own parameters (chapter 06: --fixed-epsilon,
    // ...): each is a command-line option and a control in the overlay.
    std::function<void(Params&, RtChapterSettings&)> options;
    // chapter 14 on: lights in physical units (power, irradiance), no
    // ambient light unless the scene gives it; earlier chapters refuse them
    bool physicalLights = false;
    // chapter 14 on: changes the pipeline's shaders for the scene before the
    // pipeline is made (--caustics transmit's any-hit and miss shaders)
    std::function<void(RtShaders&, const Scene&)> adaptShaders;
    // chapter 14 on: made once the scene is uploaded (FramePass)
    std::function<FramePass(const FramePassContext&)> framePass;
};

int runRtChapter(int argc, char** argv, const RtChapter& chapter);

}  // namespace rg
