#include "raytracing/accel.h"

#include "scene/mesh.h"
#include "vk_check.h"
#include "vulkan/gpu_timer.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <stdexcept>

namespace rg {

namespace {

// [region create_as]
// An acceleration structure is a view of a buffer (like an image view of an
// image): make the buffer, then the structure on it. Its address is what a
// TLAS instance (or, for the TLAS, the shader's descriptor) refers to.
AccelerationStructure createAccelerationStructure(const Gpu& gpu, DeletionQueue& deletion,
                                                  VkAccelerationStructureTypeKHR type,
                                                  VkDeviceSize size) {
    AccelerationStructure as;
    as.buffer = createBuffer(gpu, deletion, size,
                             VK_BUFFER_USAGE_ACCELERATION_STRUCTURE_STORAGE_BIT_KHR |
                                 VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT,
                             VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
    VkAccelerationStructureCreateInfoKHR info{
        .sType = VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_CREATE_INFO_KHR,
        .buffer = as.buffer.handle,
        .size = size,
        .type = type,
    };
    VK_CHECK(vkCreateAccelerationStructureKHR(gpu.device, &info, nullptr, &as.handle));
    VkDevice device = gpu.device;
    VkAccelerationStructureKHR handle = as.handle;
    deletion.push(
        [device, handle] { vkDestroyAccelerationStructureKHR(device, handle, nullptr); });
    VkAccelerationStructureDeviceAddressInfoKHR address{
        .sType = VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_DEVICE_ADDRESS_INFO_KHR,
        .accelerationStructure = as.handle,
    };
    as.address = vkGetAccelerationStructureDeviceAddressKHR(gpu.device, &address);
    return as;
}
// [end]

VkDeviceSize alignUp(VkDeviceSize value, VkDeviceSize alignment) {
    return (value + alignment - 1) / alignment * alignment;
}

// A barrier between acceleration structure builds/copies and what follows.
void accelBarrier(VkCommandBuffer cmd, VkPipelineStageFlags dstStage,
                  VkAccessFlags dstAccess) {
    VkMemoryBarrier barrier{
        .sType = VK_STRUCTURE_TYPE_MEMORY_BARRIER,
        .srcAccessMask = VK_ACCESS_ACCELERATION_STRUCTURE_WRITE_BIT_KHR,
        .dstAccessMask = dstAccess,
    };
    vkCmdPipelineBarrier(cmd,
                         // after the build
                         VK_PIPELINE_STAGE_ACCELERATION_STRUCTURE_BUILD_BIT_KHR,
                         // before its users
                         dstStage,
                         0, 1, &barrier, 0, nullptr, 0, nullptr);
}

}  // namespace

// [region build_blas]
// Builds one BLAS with PREFER_FAST_TRACE | ALLOW_COMPACTION, asks the GPU for
// its compacted size, copies it into a structure of exactly that size and
// frees the original. Scenes are static at the BLAS level, so the smaller
// copy is all that is kept.
AccelerationStructure buildCompactedBlas(
    const Gpu& gpu, DeletionQueue& deletion,
    const VkAccelerationStructureGeometryKHR& geometry, uint32_t primitiveCount,
    BlasStats& stats) {
    VkAccelerationStructureBuildGeometryInfoKHR build{
        .sType = VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_BUILD_GEOMETRY_INFO_KHR,
        .type = VK_ACCELERATION_STRUCTURE_TYPE_BOTTOM_LEVEL_KHR,
        .flags = VK_BUILD_ACCELERATION_STRUCTURE_PREFER_FAST_TRACE_BIT_KHR |
                 VK_BUILD_ACCELERATION_STRUCTURE_ALLOW_COMPACTION_BIT_KHR,
        .mode = VK_BUILD_ACCELERATION_STRUCTURE_MODE_BUILD_KHR,
        .geometryCount = 1,
        .pGeometries = &geometry,
    };
    VkAccelerationStructureBuildSizesInfoKHR sizes{
        .sType = VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_BUILD_SIZES_INFO_KHR};
    vkGetAccelerationStructureBuildSizesKHR(
        gpu.device, VK_ACCELERATION_STRUCTURE_BUILD_TYPE_DEVICE_KHR, &build,
        &primitiveCount, &sizes);

    DeletionQueue temporary;  // the uncompacted BLAS and the scratch memory
    AccelerationStructure full = createAccelerationStructure(
        gpu, temporary, build.type, sizes.accelerationStructureSize);
    VkDeviceSize scratchAlign =
        gpu.physical.accelerationStructure.minAccelerationStructureScratchOffsetAlignment;
    Buffer scratch = createBuffer(
        gpu, temporary, sizes.buildScratchSize + scratchAlign,
        VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT,
        VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
    build.dstAccelerationStructure = full.handle;
    build.scratchData.deviceAddress = alignUp(scratch.address, scratchAlign);

    VkQueryPoolCreateInfo queryInfo{
        .sType = VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO,
        .queryType = VK_QUERY_TYPE_ACCELERATION_STRUCTURE_COMPACTED_SIZE_KHR,
        .queryCount = 1,
    };
    VkQueryPool query = VK_NULL_HANDLE;
    VK_CHECK(vkCreateQueryPool(gpu.device, &queryInfo, nullptr, &query));
    VkDevice device = gpu.device;
    temporary.push([device, query] { vkDestroyQueryPool(device, query, nullptr); });
    vkResetQueryPool(gpu.device, query, 0, 1);

    GpuTimer timer(gpu, temporary, 2);
    VkAccelerationStructureBuildRangeInfoKHR range{.primitiveCount = primitiveCount};
    const VkAccelerationStructureBuildRangeInfoKHR* ranges = &range;
    submitOnce(gpu, [&](VkCommandBuffer cmd) {
        timer.begin(cmd, 0);
        vkCmdBuildAccelerationStructuresKHR(cmd, 1, &build, &ranges);
        timer.end(cmd, 0);
        // The compacted size is known only once the build has finished.
        accelBarrier(cmd, VK_PIPELINE_STAGE_ACCELERATION_STRUCTURE_BUILD_BIT_KHR,
                     VK_ACCESS_ACCELERATION_STRUCTURE_READ_BIT_KHR);
        vkCmdWriteAccelerationStructuresPropertiesKHR(
            cmd, 1, &full.handle, VK_QUERY_TYPE_ACCELERATION_STRUCTURE_COMPACTED_SIZE_KHR,
            query, 0);
    });
    VkDeviceSize compactSize = 0;
    VK_CHECK(vkGetQueryPoolResults(gpu.device, query, 0, 1, sizeof(compactSize),
                                   &compactSize, sizeof(compactSize),
                                   VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT));

    AccelerationStructure compact =
        createAccelerationStructure(gpu, deletion, build.type, compactSize);
    submitOnce(gpu, [&](VkCommandBuffer cmd) {
        timer.begin(cmd, 1);
        VkCopyAccelerationStructureInfoKHR copy{
            .sType = VK_STRUCTURE_TYPE_COPY_ACCELERATION_STRUCTURE_INFO_KHR,
            .src = full.handle,
            .dst = compact.handle,
            .mode = VK_COPY_ACCELERATION_STRUCTURE_MODE_COMPACT_KHR,
        };
        vkCmdCopyAccelerationStructureKHR(cmd, &copy);
        timer.end(cmd, 1);
    });
    stats.buildBytes = sizes.accelerationStructureSize;
    stats.compactBytes = compactSize;
    stats.buildMs = timer.readMs(0);
    stats.compactMs = timer.readMs(1);
    return compact;  // `temporary` frees the original now: the copy has finished
}
// [end]


// [region unit_shapes]
// A geometry of boxes, VkAabbPositionsKHR one after another in `boxes`.
VkAccelerationStructureGeometryKHR aabbGeometry(const Buffer& boxes) {
    return {
        .sType = VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_GEOMETRY_KHR,
        .geometryType = VK_GEOMETRY_TYPE_AABBS_KHR,
        .geometry = {.aabbs = {
            .sType = VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_GEOMETRY_AABBS_DATA_KHR,
            .data = {.deviceAddress = boxes.address},
            .stride = sizeof(VkAabbPositionsKHR),
        }},
        // no any-hit shader: the first hit is the hit. Where a ray makes it
        // run anyway (chapter 14's transmitted shadows), once per hit.
        .flags = VK_GEOMETRY_OPAQUE_BIT_KHR |
                 VK_GEOMETRY_NO_DUPLICATE_ANY_HIT_INVOCATION_BIT_KHR,
    };
}

// Indexed triangles: float x, y, z vertices one after another, uint32 indices.
VkAccelerationStructureGeometryKHR triangleGeometry(const Buffer& vertices,
                                                    uint32_t maxVertex,
                                                    const Buffer& indices) {
    return {
        .sType = VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_GEOMETRY_KHR,
        .geometryType = VK_GEOMETRY_TYPE_TRIANGLES_KHR,
        .geometry = {.triangles = {
            .sType = VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_GEOMETRY_TRIANGLES_DATA_KHR,
            .vertexFormat = VK_FORMAT_R32G32B32_SFLOAT,
            .vertexData = {.deviceAddress = vertices.address},
            .vertexStride = 3 * sizeof(float),
            .maxVertex = maxVertex,
            .indexType = VK_INDEX_TYPE_UINT32,
            .indexData = {.deviceAddress = indices.address},
        }},
        // no any-hit shader: the first hit is the hit (once per hit where a
        // ray or an instance makes it run: alpha tests, transmitted shadows)
        .flags = VK_GEOMETRY_OPAQUE_BIT_KHR |
                 VK_GEOMETRY_NO_DUPLICATE_ANY_HIT_INVOCATION_BIT_KHR,
    };
}

UnitShapes buildUnitShapes(const Gpu& gpu, DeletionQueue& deletion, int sphereMeshLevel,
                           const Scene* scene, bool fileOrder, TriangleTest test) {
    UnitShapes shapes;
    DeletionQueue inputs;  // vertex, index and AABB data are not needed after the build
    const VkBufferUsageFlags input =
        VK_BUFFER_USAGE_ACCELERATION_STRUCTURE_BUILD_INPUT_READ_ONLY_BIT_KHR |
        VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT;

    // The unit quad: y = 0, facing +y, two triangles.
    const float vertices[] = {-1, 0, -1, 1, 0, -1, 1, 0, 1, -1, 0, 1};
    const uint32_t indices[] = {0, 2, 1, 0, 3, 2};
    Buffer vertexBuffer =
        createDeviceBuffer(gpu, inputs, vertices, sizeof(vertices), input);
    Buffer indexBuffer = createDeviceBuffer(gpu, inputs, indices, sizeof(indices), input);
    VkAccelerationStructureGeometryKHR triangles =
        triangleGeometry(vertexBuffer, 3, indexBuffer);
    shapes.stats.push_back({.name = "unit_quad", .geometry = "triangles"});
    shapes.quad = buildCompactedBlas(gpu, deletion, triangles, 2, shapes.stats.back());

    // The unit sphere: only its bounding box goes into the BLAS. The
    // traversal calls the intersection shader for rays that enter the box.
    const VkAabbPositionsKHR box{-1, -1, -1, 1, 1, 1};
    Buffer aabbBuffer = createDeviceBuffer(gpu, inputs, &box, sizeof(box), input);
    VkAccelerationStructureGeometryKHR aabbs = aabbGeometry(aabbBuffer);
    shapes.stats.push_back({.name = "unit_sphere", .geometry = "aabbs"});
    shapes.sphere = buildCompactedBlas(gpu, deletion, aabbs, 1, shapes.stats.back());
    // [end]

    // Chapter 12: each mesh of the scene once, however many objects place it.
    if (scene)
        for (const auto& mesh : scene->meshes) {
            shapes.stats.push_back({.name = mesh->name});
            if (fileOrder) {
                shapes.meshes.push_back(
                    buildMeshBlas(gpu, deletion, *mesh, shapes.stats.back(), test));
            } else {
                Mesh ordered = *mesh;
                medianSplitTriangles(ordered);
                shapes.meshes.push_back(
                    buildMeshBlas(gpu, deletion, ordered, shapes.stats.back(), test));
            }
        }
    if (sphereMeshLevel > 0) {  // the tessellated alternative (performance.md)
        shapes.stats.push_back({.name = "icosphere_" + std::to_string(sphereMeshLevel)});
        shapes.sphereMesh = int(shapes.meshes.size());
        shapes.meshes.push_back(buildMeshBlas(gpu, deletion, icosphere(sphereMeshLevel),
                                              shapes.stats.back(), test));
    }
    return shapes;
}


// [region transform]
VkTransformMatrixKHR toVkTransform(const glm::dmat4& m) {
    VkTransformMatrixKHR t;  // 3 rows x 4 columns, row-major; glm is column-major
    for (int row = 0; row < 3; ++row)
        for (int col = 0; col < 4; ++col) t.matrix[row][col] = float(m[col][row]);
    return t;
}
// [end]

bool inSphereGroup(const Object& o) {
    if (o.type != ShapeType::Sphere || o.moving || o.hidden) return false;
    glm::dvec3 x(o.transform[0]), y(o.transform[1]), z(o.transform[2]);
    double r2 = glm::dot(x, x), tolerance = 1e-12 * r2;
    return std::abs(glm::dot(y, y) - r2) <= tolerance &&
           std::abs(glm::dot(z, z) - r2) <= tolerance &&
           std::abs(glm::dot(x, y)) <= tolerance &&
           std::abs(glm::dot(y, z)) <= tolerance && std::abs(glm::dot(z, x)) <= tolerance;
}

glm::dvec4 groupSphere(const Object& o) {
    return glm::dvec4(glm::dvec3(o.transform[3]),
                      glm::length(glm::dvec3(o.transform[0])));
}

// [region sphere_group]
SphereGroup buildSphereGroup(const Gpu& gpu, DeletionQueue& deletion, const Scene& scene,
                             const std::vector<uint32_t>& objects, uint32_t firstObject) {
    SphereGroup group{.objects = objects, .firstObject = firstObject};
    std::vector<VkAabbPositionsKHR> boxes;
    // in the order given: lavapipe's tree is this list (chapter 03)
    for (uint32_t i : objects) {
        // Rounded outwards to float, so that no part of the sphere is outside its box.
        auto down = [](double v) { return std::nextafter(float(v), -INFINITY); };
        auto up = [](double v) { return std::nextafter(float(v), INFINITY); };
        glm::dvec4 sphere = groupSphere(scene.objects[i]);
        glm::dvec3 lo = glm::dvec3(sphere) - sphere.w, hi = glm::dvec3(sphere) + sphere.w;
        boxes.push_back(
            {down(lo.x), down(lo.y), down(lo.z), up(hi.x), up(hi.y), up(hi.z)});
    }
    group.stats = {.name = "sphere_group", .geometry = "aabbs"};
    if (boxes.empty()) return group;
    DeletionQueue inputs;  // the boxes are not needed after the build
    Buffer boxBuffer = createDeviceBuffer(
        gpu, inputs, boxes.data(), boxes.size() * sizeof(VkAabbPositionsKHR),
        VK_BUFFER_USAGE_ACCELERATION_STRUCTURE_BUILD_INPUT_READ_ONLY_BIT_KHR |
            VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT);
    group.blas = buildCompactedBlas(gpu, deletion, aabbGeometry(boxBuffer),
                                    uint32_t(boxes.size()), group.stats);
    return group;
}
// [end]

// [region make_instances]
std::vector<VkAccelerationStructureInstanceKHR> makeInstances(
    const Scene& scene, const UnitShapes& shapes, const std::vector<uint32_t>& objects,
    const SphereGroup* group) {
    std::vector<VkAccelerationStructureInstanceKHR> instances;
    if (group && !group->objects.empty())
        instances.push_back({
            // its boxes are where the spheres are
            .transform = toVkTransform(glm::dmat4(1.0)),
            .instanceCustomIndex = group->firstObject,
            .mask = 0xFFu,
            // the analytic sphere's hit group
            .instanceShaderBindingTableRecordOffset = 1u,
            .flags = 0,
            .accelerationStructureReference = group->blas.address,
        });
    for (uint32_t i : objects) {
        const Object& o = scene.objects[i];
        bool sphere = o.type == ShapeType::Sphere;
        // --sphere-mesh
        int mesh = o.type == ShapeType::Mesh ? int(o.mesh)
                   : sphere                  ? shapes.sphereMesh
                                             : -1;
        instances.push_back({
            .transform = toVkTransform(o.transform),
            .instanceCustomIndex = uint32_t(i),  // gl_InstanceCustomIndexEXT: the object
            // every ray sees every instance, but a hidden copy
            .mask = o.hidden ? 0x00u : 0xFFu,
            // hit group
            .instanceShaderBindingTableRecordOffset = mesh >= 0 ? 2u
                                                      : sphere  ? 1u
                                                                : 0u,
            // both sides of every triangle; an alpha-tested mesh (chapter
            // 12) not opaque, so that its any-hit shader runs
            .flags = VK_GEOMETRY_INSTANCE_TRIANGLE_FACING_CULL_DISABLE_BIT_KHR |
                     (mesh >= 0 && alphaTested(scene, o)
                          ? uint32_t(VK_GEOMETRY_INSTANCE_FORCE_NO_OPAQUE_BIT_KHR)
                          : 0u),
            .accelerationStructureReference = mesh >= 0 ? shapes.meshes[mesh].blas.address
                                              : sphere  ? shapes.sphere.address
                                                        : shapes.quad.address,
        });
    }
    return instances;
}
// [end]

namespace {
VkAccelerationStructureGeometryKHR instanceGeometry(const Buffer& instances) {
    return {
        .sType = VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_GEOMETRY_KHR,
        .geometryType = VK_GEOMETRY_TYPE_INSTANCES_KHR,
        .geometry = {.instances = {
            .sType = VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_GEOMETRY_INSTANCES_DATA_KHR,
            .arrayOfPointers = VK_FALSE,
            .data = {.deviceAddress = instances.address},
        }},
    };
}
}  // namespace

// [region build_tlas]
Tlas buildTlas(const Gpu& gpu, DeletionQueue& deletion,
               const std::vector<VkAccelerationStructureInstanceKHR>& instances) {
    Tlas tlas;
    tlas.count = uint32_t(instances.size());
    VkDeviceSize bytes = instances.size() * sizeof(VkAccelerationStructureInstanceKHR);
    tlas.instances = createDeviceBuffer(
        gpu, deletion, instances.data(), bytes,
        VK_BUFFER_USAGE_ACCELERATION_STRUCTURE_BUILD_INPUT_READ_ONLY_BIT_KHR |
            VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT |
            VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);

    VkAccelerationStructureGeometryKHR geometry = instanceGeometry(tlas.instances);
    VkAccelerationStructureBuildGeometryInfoKHR build{
        .sType = VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_BUILD_GEOMETRY_INFO_KHR,
        .type = VK_ACCELERATION_STRUCTURE_TYPE_TOP_LEVEL_KHR,
        // ALLOW_UPDATE: moving an object only changes its transform, so the
        // TLAS is refitted in place each frame instead of rebuilt (see the docs).
        .flags = VK_BUILD_ACCELERATION_STRUCTURE_PREFER_FAST_TRACE_BIT_KHR |
                 VK_BUILD_ACCELERATION_STRUCTURE_ALLOW_UPDATE_BIT_KHR,
        .mode = VK_BUILD_ACCELERATION_STRUCTURE_MODE_BUILD_KHR,
        .geometryCount = 1,
        .pGeometries = &geometry,
    };
    VkAccelerationStructureBuildSizesInfoKHR sizes{
        .sType = VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_BUILD_SIZES_INFO_KHR};
    vkGetAccelerationStructureBuildSizesKHR(
        gpu.device, VK_ACCELERATION_STRUCTURE_BUILD_TYPE_DEVICE_KHR, &build, &tlas.count,
        &sizes);
    tlas.buildBytes = sizes.accelerationStructureSize;
    tlas.updateScratchBytes = sizes.updateScratchSize;
    tlas.as = createAccelerationStructure(gpu, deletion, build.type,
                                          sizes.accelerationStructureSize);
    VkDeviceSize scratchAlign =
        gpu.physical.accelerationStructure.minAccelerationStructureScratchOffsetAlignment;
    tlas.scratch = createBuffer(
        gpu, deletion,
        std::max(sizes.buildScratchSize, sizes.updateScratchSize) + scratchAlign,
        VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT,
        VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
    build.dstAccelerationStructure = tlas.as.handle;
    tlas.scratchAddress = alignUp(tlas.scratch.address, scratchAlign);
    build.scratchData.deviceAddress = tlas.scratchAddress;
    VkAccelerationStructureBuildRangeInfoKHR range{.primitiveCount = tlas.count};
    const VkAccelerationStructureBuildRangeInfoKHR* ranges = &range;
    DeletionQueue local;
    GpuTimer timer(gpu, local, 1);
    submitOnce(gpu, [&](VkCommandBuffer cmd) {
        timer.begin(cmd, 0);
        vkCmdBuildAccelerationStructuresKHR(cmd, 1, &build, &ranges);
        timer.end(cmd, 0);
    });
    tlas.buildMs = timer.readMs(0);
    return tlas;
}

void recordTlasUpdate(VkCommandBuffer cmd, const Tlas& tlas,
                      const std::vector<VkAccelerationStructureInstanceKHR>& instances,
                      const std::vector<uint32_t>& changed,
                      VkPipelineStageFlags consumerStage) {
    if (instances.size() != tlas.count)
        throw std::runtime_error("recordTlasUpdate: needs the TLAS's own instances");
    // The previous frame's rays and refit must be done with the instances
    // and the TLAS before this frame overwrites them.
    VkMemoryBarrier readsDone{
        .sType = VK_STRUCTURE_TYPE_MEMORY_BARRIER,
        .srcAccessMask = VK_ACCESS_ACCELERATION_STRUCTURE_WRITE_BIT_KHR,
        .dstAccessMask =
            VK_ACCESS_TRANSFER_WRITE_BIT | VK_ACCESS_ACCELERATION_STRUCTURE_WRITE_BIT_KHR,
    };
    vkCmdPipelineBarrier(
        cmd,
        // earlier users
        consumerStage | VK_PIPELINE_STAGE_ACCELERATION_STRUCTURE_BUILD_BIT_KHR,
        VK_PIPELINE_STAGE_TRANSFER_BIT |
            VK_PIPELINE_STAGE_ACCELERATION_STRUCTURE_BUILD_BIT_KHR,
        0, 1, &readsDone, 0, nullptr, 0, nullptr);
    // The changed instances travel inside the command buffer, 64 bytes each:
    // no host-visible memory that a frame in flight still reads, and a
    // million static instances are not sent again.
    for (uint32_t k : changed)
        vkCmdUpdateBuffer(cmd, tlas.instances.handle, k * sizeof(instances[0]),
                          sizeof(instances[0]), &instances[k]);
    VkMemoryBarrier written{
        .sType = VK_STRUCTURE_TYPE_MEMORY_BARRIER,
        .srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT,
        .dstAccessMask =
            VK_ACCESS_ACCELERATION_STRUCTURE_READ_BIT_KHR | VK_ACCESS_SHADER_READ_BIT,
    };
    vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT,
                         VK_PIPELINE_STAGE_ACCELERATION_STRUCTURE_BUILD_BIT_KHR, 0, 1,
                         &written, 0, nullptr, 0, nullptr);

    VkAccelerationStructureGeometryKHR geometry = instanceGeometry(tlas.instances);
    VkAccelerationStructureBuildGeometryInfoKHR update{
        .sType = VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_BUILD_GEOMETRY_INFO_KHR,
        .type = VK_ACCELERATION_STRUCTURE_TYPE_TOP_LEVEL_KHR,
        .flags = VK_BUILD_ACCELERATION_STRUCTURE_PREFER_FAST_TRACE_BIT_KHR |
                 // must match the build's flags
                 VK_BUILD_ACCELERATION_STRUCTURE_ALLOW_UPDATE_BIT_KHR,
        .mode = VK_BUILD_ACCELERATION_STRUCTURE_MODE_UPDATE_KHR,
        .srcAccelerationStructure = tlas.as.handle,  // updated in place: src == dst
        .dstAccelerationStructure = tlas.as.handle,
        .geometryCount = 1,
        .pGeometries = &geometry,
        .scratchData = {.deviceAddress = tlas.scratchAddress},
    };
    VkAccelerationStructureBuildRangeInfoKHR range{.primitiveCount = tlas.count};
    const VkAccelerationStructureBuildRangeInfoKHR* ranges = &range;
    vkCmdBuildAccelerationStructuresKHR(cmd, 1, &update, &ranges);
    // Ray tracing shaders read the TLAS itself. Any other shader stage can
    // read a structure only through ray queries, so without that feature a
    // barrier may not name ACCELERATION_STRUCTURE_READ for it
    // (VUID-vkCmdPipelineBarrier-dstAccessMask-06257): chapter 03's compute
    // shader reads the instance buffer (SHADER_READ), not the structure.
    VkAccessFlags reads = VK_ACCESS_SHADER_READ_BIT;
    if (consumerStage & VK_PIPELINE_STAGE_RAY_TRACING_SHADER_BIT_KHR)
        reads |= VK_ACCESS_ACCELERATION_STRUCTURE_READ_BIT_KHR;
    accelBarrier(cmd, consumerStage, reads);
}
// [end]

}  // namespace rg
