#include "raytracing/two_launches.h"

#include <algorithm>
#include <cstring>

namespace rg {

TwoLaunches createTwoLaunches(const Gpu& gpu, DeletionQueue& deletion,
                              VkDescriptorSetLayout setLayout, RtShaders shaders,
                              uint32_t pixels) {
    TwoLaunches t{.capacity = std::max(1u, pixels / 4)};
    shaders.raygenConstant = LAUNCH_FIRST;
    t.first = createRtPipeline(gpu, deletion, setLayout, sizeof(gpu::RtPush), shaders);
    shaders.raygenConstant = LAUNCH_QUEUED;
    t.queued = createRtPipeline(gpu, deletion, setLayout, sizeof(gpu::RtPush), shaders);
    t.queue = createBuffer(
        gpu, deletion,
        TREE_QUEUE_HEADER_BYTES + VkDeviceSize(t.capacity) * sizeof(gpu::QueuedTree),
        VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT |
            VK_BUFFER_USAGE_TRANSFER_DST_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT |
            VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT,
        VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
    t.counts =
        createHostBuffer(gpu, deletion, FrameLoop::kFramesInFlight * sizeof(uint32_t),
                         VK_BUFFER_USAGE_TRANSFER_DST_BIT);
    std::memset(t.counts.mapped, 0, FrameLoop::kFramesInFlight * sizeof(uint32_t));
    return t;
}

// [region two_launches]
void recordLaunches(VkCommandBuffer cmd, TwoLaunches& t, const RtPipeline& one,
                    VkDescriptorSet set, gpu::RtPush push, uint32_t width,
                    uint32_t height, Launches mode, uint32_t frame) {
    // This frame slot's count was copied by the frame before last, whose
    // fence the frame loop has waited for; the first frames have none yet.
    uint32_t slot = frame % FrameLoop::kFramesInFlight;
    uint32_t trees = static_cast<const uint32_t*>(t.counts.mapped)[slot];
    bool counted = frame >= FrameLoop::kFramesInFlight;
    bool two = mode == Launches::Two || (mode == Launches::Auto && counted &&
                                         trees < kTwoLaunchesBelow * width * height);
    t.lastFrame = frame;
    t.lastLaunches = two ? 2 : 1;

    constexpr VkPipelineStageFlags rt = VK_PIPELINE_STAGE_RAY_TRACING_SHADER_BIT_KHR;
    // The previous frame's launches must be done with the queue before it is reset.
    memoryBarrier(
        cmd, rt | VK_PIPELINE_STAGE_DRAW_INDIRECT_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT,
        VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT |
            VK_ACCESS_INDIRECT_COMMAND_READ_BIT | VK_ACCESS_TRANSFER_READ_BIT,
        VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT);
    const uint32_t header[4] = {0, 1, 1, t.capacity};  // count, height, depth, capacity
    vkCmdUpdateBuffer(cmd, t.queue.handle, 0, sizeof(header), header);
    memoryBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT, rt,
                  VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT);

    push.treeQueue = {uint32_t(t.queue.address), uint32_t(t.queue.address >> 32)};
    // one: it counts the trees
    recordTrace(cmd, two ? t.first : one, set, &push, sizeof(push), width, height);
    if (two) {
        // The queue's count becomes the second launch's width: the GPU reads
        // it as an indirect command, the shaders read the trees.
        memoryBarrier(cmd, rt, VK_ACCESS_SHADER_WRITE_BIT,
                      rt | VK_PIPELINE_STAGE_DRAW_INDIRECT_BIT,
                      VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT |
                          VK_ACCESS_INDIRECT_COMMAND_READ_BIT);
        vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_RAY_TRACING_KHR, t.queued.pipeline);
        vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_RAY_TRACING_KHR,
                                t.queued.layout, 0, 1, &set, 0, nullptr);
        vkCmdPushConstants(cmd, t.queued.layout, kRtPushStages, 0, sizeof(push), &push);
        vkCmdTraceRaysIndirectKHR(cmd, &t.queued.raygen, &t.queued.miss, &t.queued.hit,
                                  &t.queued.callable,
                                  // VkTraceRaysIndirectCommandKHR{count, 1, 1}
                                  t.queue.address);
    }

    // The count, for the frame that will use this slot next.
    memoryBarrier(cmd, rt, VK_ACCESS_SHADER_WRITE_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT,
                  VK_ACCESS_TRANSFER_READ_BIT);
    VkBufferCopy region{
        .srcOffset = 0, .dstOffset = slot * sizeof(uint32_t), .size = sizeof(uint32_t)};
    vkCmdCopyBuffer(cmd, t.queue.handle, t.counts.handle, 1, &region);
    memoryBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT,
                  VK_PIPELINE_STAGE_HOST_BIT, VK_ACCESS_HOST_READ_BIT);
}
// [end]

uint32_t lastTrees(const TwoLaunches& t) {
    return static_cast<const uint32_t*>(
        t.counts.mapped)[t.lastFrame % FrameLoop::kFramesInFlight];
}

}  // namespace rg
