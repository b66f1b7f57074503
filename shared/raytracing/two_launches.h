// Chapter 10's two launches (docs/10_refraction.md, "Two launches"): the
// first traces every pixel's camera ray and queues the pixels whose ray tree
// goes on; the second, as wide as the queue (an indirect launch), traces
// those trees. A warp of the first launch no longer waits for its one lane
// whose tree is deep. It pays where few pixels have trees (big scenes); where
// many have, one launch is faster, so by default each frame chooses.
#pragma once
#include "host_device.h"
#include "raytracing/rt_pipeline.h"
#include "vulkan/context.h"
#include "vulkan/frame_loop.h"
#include "vulkan/resources.h"

namespace rg {

enum class Launches { Auto = 0, One = 1, Two = 2 };  // --launches auto|one|two

// auto: two launches while fewer than this share of the pixels had a tree
// going on past the first hit, two frames ago (measured: performance.md);
// the first two frames, which have no count yet, take one.
constexpr double kTwoLaunchesBelow = 0.06;

struct TwoLaunches {
    // the chapter's shaders, the ray generation shader specialized for each launch
    RtPipeline first, queued;
    // TREE_QUEUE_HEADER_BYTES of header, then gpu::QueuedTree[capacity]
    Buffer queue;
    // host-visible: each frame slot's count of trees, copied at the frame's end
    Buffer counts;
    // trees the queue holds: a quarter of the pixels it was made for
    uint32_t capacity = 0;
    uint32_t lastFrame = 0, lastLaunches = 1;  // what the last recorded frame did
};

// Room for the trees of a quarter of the pixels; a pixel that finds the
// queue full traces its tree in the first launch, as one launch would.
TwoLaunches createTwoLaunches(const Gpu& gpu, DeletionQueue& deletion,
                              VkDescriptorSetLayout setLayout, RtShaders shaders,
                              uint32_t pixels);

// Records one frame: `one` (the chapter's pipeline) or the two launches, as
// `mode` says, and copies the count of trees for the frames to come.
void recordLaunches(VkCommandBuffer cmd, TwoLaunches& launches, const RtPipeline& one,
                    VkDescriptorSet set, gpu::RtPush push, uint32_t width,
                    uint32_t height, Launches mode, uint32_t frame);

// The last frame's trees past the first hit (after the frames have finished;
// with two launches it stops at the capacity).
uint32_t lastTrees(const TwoLaunches& launches);

}  // namespace rg
