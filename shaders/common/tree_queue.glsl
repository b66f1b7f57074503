// Chapter 10's second launch: the first launch queues each pixel whose ray
// tree goes on past its first hit, and the second traces those trees, so a
// warp of camera rays no longer waits for one lane's deep tree.
#ifndef TREE_QUEUE_GLSL
#define TREE_QUEUE_GLSL
#extension GL_EXT_buffer_reference : require
#extension GL_EXT_buffer_reference_uvec2 : require
#include "ray_tree.glsl"

// [region queue]
layout(buffer_reference, std430, buffer_reference_align = 16) buffer TreeQueue {
    // trees queued: the second launch's width (VkTraceRaysIndirectCommandKHR)
    uint count;
    uint height;    // 1
    uint depth;     // 1
    uint capacity;
    QueuedTree trees[];
};

// Queues the tree, its first hit traced; false when the queue is full
// (the caller then traces the rest of the tree itself).
bool queueTree(uvec2 pixel) {
    TreeQueue queue = TreeQueue(push.treeQueue);
    uint slot = atomicAdd(queue.count, 1u);
    if (slot >= queue.capacity) {
        // give the slot back: the count ends at the capacity
        atomicAdd(queue.count, 0xFFFFFFFFu);
        return false;
    }
    queue.trees[slot] = QueuedTree(Branch[2](tree.stack[0], tree.stack[1]), tree.radiance,
                                   pixel.y * uint(imageSize(target).x) + pixel.x,
                                   uint(tree.top), tree.rays,
                                   kRayCones ? floatBitsToUint(tree.coneStart) : 0u, 0u);
    return true;
}

// One launch still counts the trees that go on, so that the next frames
// can choose (shared/raytracing/two_launches.cpp); the count is all it writes.
void countTree() {
    if (push.treeQueue != uvec2(0u)) atomicAdd(TreeQueue(push.treeQueue).count, 1u);
}

// The second launch's invocation i takes tree i, as the first launch left it.
void dequeueTree(uint slot, out uvec2 pixel) {
    QueuedTree q = TreeQueue(push.treeQueue).trees[slot];
    uint width = uint(imageSize(target).x);
    pixel = uvec2(q.pixel % width, q.pixel / width);
    tree.stack[0] = q.stack[0];
    tree.stack[1] = q.stack[1];
    tree.top = int(q.top);
    tree.radiance = q.radiance;
    tree.rays = q.rays;
    tree.coneStart = uintBitsToFloat(q.coneStart);
}
// [end]
#endif
