#include "raytracing/rt_scene.h"

#include "core/files.h"
#include "host_device.h"
#include "vk_check.h"
#include "vulkan/device_limits.h"


#include <algorithm>
#include <cmath>
#include <cstring>
#include <glm/gtc/matrix_transform.hpp>

namespace rg {

// A material's shininess; where a metal-roughness texture varies it
// (chapter 12), that of its smoothest texel.
static double highestShininess(const Material& m, const Scene& scene) {
    if (m.metalRough.texture < 0) return m.shininess;
    // roughness: the texture's G, the smallest of any level (all its bytes)
    const Texture& texture = *scene.textures[m.metalRough.texture];
    uint8_t g = 255;
    for (size_t i = 1; i < texture.rgba.size(); i += 4) g = std::min(g, texture.rgba[i]);
    Material smoothest = m;
    applyMetalRoughness(smoothest, m.metalRough.baseColor, m.metalRough.metallic,
                        m.metalRough.roughness * (g / 255.0), m.transmission);
    return smoothest.shininess;
}

// [region needs_careful_rule]
CarefulNumerics needsCarefulNumerics(const Scene& scene) {
    // Near its surface a sphere's quadratic rounds by about 2^-24 of its
    // radius R (sphere_intersect.glsl's c); seen from d > R / 1024 that
    // is under 1e-4 of d, far below a pixel. Squares of lengths within
    // 1e-8..1e8 neither overflow nor underflow, with margin.
    const double kRatio = 1024.0, kSmallest = 1e-8, kLargest = 1e8;
    CarefulNumerics careful{.sizes = false, .shininess = false};
    for (const Material& m : scene.materials)
        careful.shininess = careful.shininess || highestShininess(m, scene) >= 1e4;
    // an ellipsoid's longest semi-axis over its shortest: past this, o + t d
    // in its object space loses the digits of its thin axis (sphere.rint)
    const double kSquash = 64.0;
    bool squashed = false;
    double extent = 0;         // the farthest point from the eye (the origin)
    double smallest = kLargest;  // the smallest sphere's shortest semi-axis
    for (const PointLight& light : scene.lights)
        extent = std::max(extent, glm::length(light.position));
    for (const Object& o : scene.objects) {
        const glm::dmat4& m = o.transform;
        double centre = glm::length(glm::dvec3(m[3])), stretch = largestStretch(m);
        if (o.type == ShapeType::Sphere) {
            double shortest = smallestStretch(m);
            // a plate: the intersection shader refines its hits (sphere.rint)
            squashed = squashed || stretch > kSquash * shortest;
            // the eye's distance from the surface, at least (0: it may be on it)
            double nearest = centre > stretch     ? centre - stretch
                             : centre < shortest ? shortest - centre
                                                 : 0.0;
            careful.sizes = careful.sizes || stretch > kRatio * nearest;
            smallest = std::min(smallest, shortest);
            extent = std::max(extent, centre + stretch);
        } else {
            // the unit quad's corners lie sqrt(2) from its centre
            double reach = std::sqrt(2.0);
            if (o.type == ShapeType::Mesh) {
                const Mesh& mesh = *scene.meshes[o.mesh];
                reach = glm::length(glm::max(glm::abs(glm::dvec3(mesh.lo)),
                                             glm::abs(glm::dvec3(mesh.hi))));
            }
            extent = std::max(extent, centre + stretch * reach);
        }
    }
    // A sphere's object space divides by its size: lengths grow by extent / smallest.
    careful.sizes = careful.sizes || extent > kLargest || smallest < kSmallest ||
                    extent > kLargest * smallest || squashed;
    return careful;
}
// [end]

CarefulNumerics carefulNumerics(const Options& opts, const Scene& scene) {
    if (opts.numerics == Numerics::Auto) return needsCarefulNumerics(scene);
    bool on = opts.numerics == Numerics::Careful;
    return {.sizes = on, .shininess = on};
}

void specialize(RtShaders& shaders, const CarefulNumerics& careful) {
    shaders.carefulSizes = careful.sizes;
    shaders.carefulShininess = careful.shininess;
}

nlohmann::json toJson(const CarefulNumerics& careful) {
    auto word = [](bool on) { return on ? "careful" : "fast"; };
    return {{"sizes", word(careful.sizes)}, {"shininess", word(careful.shininess)}};
}

void cameraMatrices(const Camera& camera, double aspect, glm::mat4& viewInverse,
                    glm::mat4& projInverse) {
    glm::dmat4 view = glm::lookAt(camera.position, camera.lookAt, camera.up);
    glm::dmat4 proj = glm::perspective(glm::radians(camera.fovYDeg), aspect, 0.1, 100.0);
    proj[1][1] *= -1;  // Vulkan's clip space y points down; the image's top row looks up
    viewInverse = glm::mat4(glm::inverse(view));
    projInverse = glm::mat4(glm::inverse(proj));
}

namespace {
template <typename T>
Buffer storage(const Gpu& gpu, DeletionQueue& deletion, const std::vector<T>& data) {
    // a binding needs a buffer
    std::vector<T> nonEmpty = data.empty() ? std::vector<T>(1) : data;
    return createDeviceBuffer(gpu, deletion, nonEmpty.data(), nonEmpty.size() * sizeof(T),
                              VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
}
glm::vec4 v4(const glm::dvec3& v, double w = 0) { return glm::vec4(glm::dvec4(v, w)); }
Buffer createRayCounts(const Gpu& gpu, DeletionQueue& deletion, uint32_t width,
                       uint32_t height) {
    return createBuffer(
        gpu, deletion, VkDeviceSize(width) * height * sizeof(uint32_t),
        VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT,
        VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
}
// A sphere's radius in world space, rounded up: a ray starting inside goes
// at most twice this far before it leaves (chapter 10); for an ellipsoid its
// longest semi-axis. A quad has no inside: 0.
float worldRadius(const Object& o) {
    if (o.type != ShapeType::Sphere) return 0.0f;
    return std::nextafter(float(largestStretch(o.transform)), INFINITY);
}
}  // namespace

static_assert(uint32_t(Glass::Diamond) == GLASS_DIAMOND &&
              uint32_t(Glass::BK7) == GLASS_BK7);

std::vector<gpu::GpuLight> toGpuLights(const Scene& scene) {
    std::vector<gpu::GpuLight> lights;
    for (const auto& l : scene.lights) {
        glm::vec3 irradiance(l.irradiance);
        if (l.kind == PointLight::Kind::Directional)  // chapter 14's sun, its disc in w
            lights.push_back({v4(l.direction, LIGHT_DIRECTIONAL),
                              glm::vec4(irradiance, float(l.angularRadius))});
        else
            lights.push_back({v4(l.position, LIGHT_POINT), v4(l.intensity)});
    }
    return lights;
}

gpu::GpuMaterial toGpuMaterial(const Material& m, const Scene& scene) {
    // chapter 12: which of the images a texture is, its size, and how it
    // wraps and filters; (0, 0, 0, 0) for none
    auto texture = [&](int index) {
        if (index < 0) return glm::uvec4(0);
        const Texture& t = *scene.textures[index];
        auto wrap = [](TextureWrap w) {
            return w == TextureWrap::Clamp    ? TEXTURE_WRAP_CLAMP
                   : w == TextureWrap::Mirror ? TEXTURE_WRAP_MIRROR
                                              : TEXTURE_WRAP_REPEAT;
        };
        return glm::uvec4(uint32_t(index), t.width, t.height,
                          wrap(t.wrapU) | wrap(t.wrapV) << TEXTURE_V_SHIFT |
                              (t.nearest ? TEXTURE_NEAREST : 0u) |
                              (t.srgb ? TEXTURE_SRGB : 0u) |
                              (t.minNearest ? TEXTURE_MIN_NEAREST : 0u) |
                              uint32_t(t.mipmap) << TEXTURE_MIPMAP_SHIFT |
                              uint32_t(t.levels.size()) << TEXTURE_LEVELS_SHIFT);
    };
    const Material::MetalRoughness& mr = m.metalRough;
    bool perHit = mr.texture >= 0;  // hitMaterial redoes the mapping
    return {v4(m.ka),
            v4(m.kd),
            v4(m.ks),
            glm::vec4(float(m.shininess), float(m.reflectivity), float(m.transmission),
                      float(m.ior)),
            glm::vec4(float(m.f0), float(m.roughness), float(m.dispersion / 20),
                      float(m.glass)),
            texture(m.texture),
            glm::vec4(glm::vec3(m.absorption), float(m.priority)),
            (m.thin ? MATERIAL_THIN : 0u) | (perHit ? MATERIAL_METAL_ROUGH : 0u),
            float(m.alphaCutoff),
            float(m.alpha),
            0u,
            glm::vec4(glm::vec3(mr.baseColor), float(mr.metallic)),
            glm::vec4(float(mr.roughness), float(m.normalScale), 0, 0),
            texture(mr.texture),
            texture(m.normalTexture)};
}

// The scene's buffers and structures against the device's limits, before
// they are made: the largest storage buffers (objects, the sky's texels),
// the textures' images and the instance and box counts of the acceleration
// structures.
void checkSceneFits(const Gpu& gpu, const Scene& scene, const SkyTexels& sky,
                    size_t grouped, size_t instanced) {
    std::string name;
    double limit = storageBufferLimit(gpu, &name);
    checkTexturesFit(gpu, scene);
    double skyBytes = double(sky.rgba.size()) * sizeof(float);
    if (skyBytes > limit) {
        double texels = std::floor(limit / 16),
               scale = std::sqrt(texels / (double(sky.width) * sky.height));
        throw InputError(scene.path + ": sky.image: its " + std::to_string(sky.width) +
                         "x" + std::to_string(sky.height) + " texels need " +
                         mebibytes(skyBytes) +
                         " in one storage buffer, more than this device's " + name +
                         " (" + mebibytes(limit) + "); an image of at most " +
                         std::to_string(uint32_t(sky.width * scale)) + "x" +
                         std::to_string(uint32_t(sky.height * scale)) + " fits");
    }
    double objectBytes = double(scene.objects.size() + grouped) * sizeof(gpu::GpuObject);
    if (objectBytes > limit)
        throw InputError(scene.path +
                         ": objects: " + std::to_string(scene.objects.size()) +
                         " objects need " + mebibytes(objectBytes) +
                         " in one storage buffer, more than this device's " + name +
                         " (" + mebibytes(limit) + "); at most " +
                         std::to_string(uint64_t(limit / (2 * sizeof(gpu::GpuObject)))) +
                         " spheres fit");
    const auto& as = gpu.physical.accelerationStructure;
    for (const auto& mesh : scene.meshes)
        if (mesh->indices.size() / 3 > as.maxPrimitiveCount)
            throw InputError(scene.path + ": " + mesh->name + ": " +
                             std::to_string(mesh->indices.size() / 3) +
                             " triangles, more than this device's maxPrimitiveCount (" +
                             std::to_string(as.maxPrimitiveCount) + ")");
    if (instanced + 1 > as.maxInstanceCount)
        throw InputError(scene.path + ": objects: " + std::to_string(instanced) +
                         " instances, more than this device's maxInstanceCount (" +
                         std::to_string(as.maxInstanceCount) + ")");
    if (grouped > as.maxPrimitiveCount)
        throw InputError(
            scene.path + ": objects: " + std::to_string(grouped) +
            " spheres in one group, more than this device's maxPrimitiveCount (" +
            std::to_string(as.maxPrimitiveCount) + ")");
}

void useTriangleTest(const Gpu& gpu, RtShaders& shaders, TriangleTest test) {
    if (test == TriangleTest::Builtin) return;
    if (!gpu.physical.shaderFloat64)
        throw InputError(
            "--triangles watertight: this driver has no shaderFloat64 (double in "
            "shaders), which the test's exact edge step needs; use --triangles builtin");
    for (uint32_t group : {HIT_GROUP_MESH, RAY_TYPE_SHADOW + HIT_GROUP_MESH})
        shaders.hitGroups.at(group).intersection = "common/triangle.rint";
}

bool useAlphaTest(RtShaders& shaders, const Scene& scene) {
    bool any = false;
    for (const Object& o : scene.objects)
        any = any || (o.type == ShapeType::Mesh && alphaTested(scene, o));
    if (!any) return false;
    shaders.alphaTest = 1;
    for (uint32_t group : {HIT_GROUP_MESH, RAY_TYPE_SHADOW + HIT_GROUP_MESH})
        shaders.hitGroups.at(group).anyHit = "common/alpha.rahit";
    return true;
}

void keepLevelZero(Scene& scene) {
    for (auto& texture : scene.textures) {
        auto level0 = std::make_shared<Texture>(*texture);
        level0->levels.resize(1);
        level0->rgba.resize(4 * size_t(level0->width) * level0->height);
        texture = level0;
    }
}

bool useSunDiscs(RtShaders& shaders, const Scene& scene) {
    bool any = false;
    for (const PointLight& light : scene.lights) any = any || light.angularRadius > 0;
    shaders.sunDiscs = any;
    return any;
}

bool useMeshes(RtShaders& shaders, const RtScene& rt) {
    bool any = !rt.shapes.meshes.empty();  // the scene's, and --sphere-mesh's icosphere
    shaders.meshes = any;
    return any;
}

bool useRayCones(RtShaders& shaders, const Scene& scene) {
    bool any = false;
    for (const auto& texture : scene.textures) any = any || texture->levels.size() > 1;
    shaders.rayCones = any;
    return any;
}

bool useThinWalls(RtShaders& shaders, const Scene& scene) {
    bool any = false;
    for (const Material& m : scene.materials) any = any || m.thin;
    shaders.thinWalls = any;
    return any;
}

// [region layout]
RtScene uploadScene(const Gpu& gpu, DeletionQueue& deletion, const Scene& scene,
                    const Image& target, const SceneLayout& layout) {
    RtScene rt;
    rt.width = target.extent.width;
    rt.height = target.extent.height;
    rt.shapes = buildUnitShapes(gpu, deletion, layout.sphereMeshLevel, &scene,
                                layout.fileOrder, layout.triangles);
    // Chapter 03: which objects become boxes of the sphere group and which
    // instances, each list in the order its structure is built from.
    // a sphere mesh is instanced
    bool grouping = layout.groupSpheres && layout.sphereMeshLevel == 0;
    std::vector<uint32_t> grouped, instanced;
    for (uint32_t i = 0; i < scene.objects.size(); ++i)
        (grouping && inSphereGroup(scene.objects[i]) ? grouped : instanced).push_back(i);
    if (!layout.fileOrder) {
        grouped = medianSplitOrder(scene, std::move(grouped));
        instanced = medianSplitOrder(scene, std::move(instanced));
    }
    SkyTexels sky = loadSky(scene);
    checkSceneFits(gpu, scene, sky, grouped.size(), instanced.size());
    // The group's entries go after the scene's own objects in the GPU's array.
    rt.group =
        buildSphereGroup(gpu, deletion, scene, grouped, uint32_t(scene.objects.size()));
    rt.instances = makeInstances(scene, rt.shapes, instanced, &rt.group);
    rt.tlas = buildTlas(gpu, deletion, rt.instances);
// [end]

    gpu::RtCamera camera{};
    cameraMatrices(scene.camera, double(rt.width) / rt.height, camera.viewInverse,
                   camera.projInverse);
    camera.skyTop = v4(scene.sky.top);
    camera.skyHorizon = v4(scene.sky.horizon);
    camera.skyBottom = v4(scene.sky.bottom);
    camera.ambient = v4(scene.ambient);
    camera.counts = {sky.width, sky.height, uint32_t(scene.lights.size()),
                     uint32_t(scene.objects.size())};
    camera.eyeTmin = float(scene.eyeTmin);
    camera.eyeMedium = uint32_t(scene.cameraMedium + 1);
    rt.camera = createDeviceBuffer(gpu, deletion, &camera, sizeof(camera),
                                   VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT);

    std::vector<gpu::GpuObject> objects;
    const glm::vec4 unitSphere(0, 0, 0, 1);  // in its instance's object space
    for (const auto& o : scene.objects) {
        bool sphereMesh = o.type == ShapeType::Sphere && rt.shapes.sphereMesh >= 0;
        uint32_t shape = o.type == ShapeType::Sphere ? SHAPE_SPHERE
                         : o.type == ShapeType::Quad ? SHAPE_QUAD
                                                     : SHAPE_MESH;
        objects.push_back({unitSphere, sphereMesh ? SHAPE_MESH : shape, o.material,
                           worldRadius(o),
                           sphereMesh ? uint32_t(rt.shapes.sphereMesh) : o.mesh});
    }
    // the group's boxes, in their order: the real spheres
    for (uint32_t i : rt.group.objects)
        objects.push_back({glm::vec4(groupSphere(scene.objects[i])), SHAPE_SPHERE,
                           scene.objects[i].material, worldRadius(scene.objects[i]), 0});
    std::vector<gpu::GpuMaterial> materials;
    for (const auto& m : scene.materials) materials.push_back(toGpuMaterial(m, scene));
    std::vector<gpu::GpuLight> lights = toGpuLights(scene);
    rt.objects = storage(gpu, deletion, objects);
    rt.materials = storage(gpu, deletion, materials);
    rt.lights = storage(gpu, deletion, lights);
    rt.sky = storage(gpu, deletion, sky.rgba);
    rt.textures = uploadTextures(gpu, deletion, scene);  // chapter 12
    rt.rayCount = createRayCounts(gpu, deletion, rt.width, rt.height);
    // [region mesh_table]
    auto address = [](const Buffer& b) {
        return glm::uvec2(uint32_t(b.address), uint32_t(b.address >> 32));
    };
    // chapter 12: one entry per mesh, its buffers by address
    std::vector<gpu::GpuMesh> meshes;
    for (const MeshBlas& m : rt.shapes.meshes)
        meshes.push_back({address(m.vertices), address(m.normals), address(m.indices),
                          address(m.texcoords)});
    // without meshes, one unused entry: a binding needs a buffer
    rt.meshes = storage(gpu, deletion, meshes);
    // [end]

    // every stage (the any-hit shader: chapter 12's alpha test)
    const VkShaderStageFlags rt_stages =
        VK_SHADER_STAGE_RAYGEN_BIT_KHR | VK_SHADER_STAGE_CLOSEST_HIT_BIT_KHR |
        VK_SHADER_STAGE_MISS_BIT_KHR | VK_SHADER_STAGE_INTERSECTION_BIT_KHR |
        VK_SHADER_STAGE_ANY_HIT_BIT_KHR;
    rt.descriptors = createDescriptorSet(
        gpu, deletion,
        {
            {RT_BINDING_TLAS, VK_DESCRIPTOR_TYPE_ACCELERATION_STRUCTURE_KHR,
             VK_SHADER_STAGE_RAYGEN_BIT_KHR},
            // and chapter 14's gather_resolve.comp
            {RT_BINDING_TARGET, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE,
             VK_SHADER_STAGE_RAYGEN_BIT_KHR | VK_SHADER_STAGE_COMPUTE_BIT},
            {RT_BINDING_CAMERA, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, rt_stages},
            {RT_BINDING_OBJECTS, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, rt_stages},
            {RT_BINDING_MATERIALS, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, rt_stages},
            {RT_BINDING_LIGHTS, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, rt_stages},
            {RT_BINDING_SKY, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, rt_stages},
            {RT_BINDING_RAY_COUNT, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER,
             VK_SHADER_STAGE_RAYGEN_BIT_KHR},
            // the closest hit, --triangles watertight's intersection shader
            // and the alpha test's any-hit shader
            {RT_BINDING_MESHES, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER,
             VK_SHADER_STAGE_CLOSEST_HIT_BIT_KHR | VK_SHADER_STAGE_INTERSECTION_BIT_KHR |
                 VK_SHADER_STAGE_ANY_HIT_BIT_KHR},
            {RT_BINDING_TEXTURES, VK_DESCRIPTOR_TYPE_SAMPLED_IMAGE,
             VK_SHADER_STAGE_CLOSEST_HIT_BIT_KHR | VK_SHADER_STAGE_ANY_HIT_BIT_KHR,
             uint32_t(rt.textures.images.size())},
        });
    // [region tlas_descriptor]
    VkDescriptorSet set = rt.descriptors.set;
    writeAccelerationStructure(gpu, set, RT_BINDING_TLAS, rt.tlas.as.handle);
    // [end]
    writeStorageImage(gpu, set, RT_BINDING_TARGET, target.view);
    writeBuffer(gpu, set, RT_BINDING_CAMERA, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER,
                rt.camera);
    writeBuffer(gpu, set, RT_BINDING_OBJECTS, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER,
                rt.objects);
    writeBuffer(gpu, set, RT_BINDING_MATERIALS, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER,
                rt.materials);
    writeBuffer(gpu, set, RT_BINDING_LIGHTS, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER,
                rt.lights);
    writeBuffer(gpu, set, RT_BINDING_SKY, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, rt.sky);
    writeBuffer(gpu, set, RT_BINDING_RAY_COUNT, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER,
                rt.rayCount);
    writeBuffer(gpu, set, RT_BINDING_MESHES, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER,
                rt.meshes);
    writeTextures(gpu, set, RT_BINDING_TEXTURES, rt.textures);
    return rt;
}

void resizeTarget(const Gpu& gpu, DeletionQueue& deletion, RtScene& rt, Image& target,
                  VkExtent2D size) {
    target = createImage2D(gpu, deletion, size.width, size.height, target.format,
                           VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT);
    rt.width = size.width;
    rt.height = size.height;
    rt.rayCount = createRayCounts(gpu, deletion, size.width, size.height);
    writeStorageImage(gpu, rt.descriptors.set, RT_BINDING_TARGET, target.view);
    writeBuffer(gpu, rt.descriptors.set, RT_BINDING_RAY_COUNT,
                VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, rt.rayCount);
}

uint64_t countRays(const Gpu& gpu, const RtScene& scene) {
    DeletionQueue local;
    VkDeviceSize bytes = scene.rayCount.size;
    Buffer host = createHostBuffer(gpu, local, bytes, VK_BUFFER_USAGE_TRANSFER_DST_BIT);
    submitOnce(gpu, [&](VkCommandBuffer cmd) {
        memoryBarrier(cmd, VK_PIPELINE_STAGE_RAY_TRACING_SHADER_BIT_KHR,
                      VK_ACCESS_SHADER_WRITE_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT,
                      VK_ACCESS_TRANSFER_READ_BIT);
        VkBufferCopy region{.size = bytes};
        vkCmdCopyBuffer(cmd, scene.rayCount.handle, host.handle, 1, &region);
        memoryBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT,
                      VK_PIPELINE_STAGE_HOST_BIT, VK_ACCESS_HOST_READ_BIT);
    });
    const uint32_t* counts = static_cast<const uint32_t*>(host.mapped);
    uint64_t total = 0;
    for (size_t i = 0; i < bytes / sizeof(uint32_t); ++i) total += counts[i];
    return total;
}

}  // namespace rg
