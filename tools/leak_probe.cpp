// Chapter 12's leak measurement: rays aimed exactly at the edges and
// vertices of closed meshes (reference/edge_rays.h) must all hit. Traced on
// the GPU through the chapters' own hit groups, once with the driver's
// triangle test and once with --triangles watertight (the boxes and
// shaders/common/triangle.rint), and by the CPU reference's test in double.
// Prints a table, and with --json every count; exit 0 unless it could not run.
//   leak_probe [--rays N] [--mesh FILE]... [--json FILE] [--validation]
#include "app/app.h"
#include "core/cli.h"
#include "core/files.h"
#include "host_device.h"
#include "raytracing/rt_pipeline.h"
#include "raytracing/rt_scene.h"
#include "reference/edge_rays.h"
#include "reference/reference.h"
#include "scene/mesh_file.h"
#include "scene/scene.h"

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <cstdio>
#include <cstring>
#include <filesystem>
#include <memory>

namespace {

// What probe.rgen pushes: the chapters' RtPush, then the probe's addresses.
struct ProbePush {
    rg::gpu::RtPush rt;
    VkDeviceAddress rays, results;
    uint32_t count, unused;
};

// Rays that did not meet the side they must: from outside a front face
// first, from inside a back face. Both kinds passed between triangles: a
// ray that met nothing (missed), or one from outside that slipped through
// the near side and met the far side from within (wrongSide).
struct Counts {
    uint64_t rays = 0, missed = 0, wrongSide = 0;
    uint64_t through() const { return missed + wrongSide; }
};
nlohmann::json toJson(const Counts& c) {
    return {{"rays", c.rays}, {"missed", c.missed}, {"wrong_side", c.wrongSide},
            {"through", c.through()}};
}

// Tallies one ray: first = 0 nothing, 1 a front face, 2 a back face.
void tally(Counts* counts, const rg::EdgeRay& ray, uint32_t first) {
    Counts& c = counts[ray.outside ? 0 : 1];
    ++c.rays;
    if (first == 0) ++c.missed;
    else if ((first == 1) != ray.outside) ++c.wrongSide;
}

// The scene the probe traces: the mesh alone, at the identity.
rg::Scene meshAlone(const std::string& file, const rg::Mesh& mesh) {
    rg::Scene scene;
    scene.path = file;
    scene.materials.push_back({.name = "probe"});
    scene.meshes.push_back(std::make_shared<rg::Mesh>(mesh));
    scene.objects.push_back({.type = rg::ShapeType::Mesh, .mesh = 0});
    return scene;
}

// The rays on the GPU with triangle test `test`: what each met first.
std::vector<uint32_t> traceOnGpu(rg::App& app, const rg::Scene& scene,
                                 const std::vector<float>& rays, rg::TriangleTest test) {
    using namespace rg;
    DeletionQueue deletion;  // this run's objects, gone when it returns
    const Gpu& gpu = app.gpu;
    uint32_t count = uint32_t(rays.size() / 6);
    Image target = createImage2D(gpu, deletion, 1, 1, VK_FORMAT_R32G32B32A32_SFLOAT,
                                 VK_IMAGE_USAGE_STORAGE_BIT);
    RtScene rt = uploadScene(gpu, deletion, scene, target, {.triangles = test});
    // the chapters' hit groups, a raygen of its own
    RtShaders shaders{
        .raygen = "leak_probe/probe.rgen",
        .miss = {"common/sky.rmiss", "common/shadow.rmiss"},
        .hitGroups = sceneHitGroups(),
    };
    useTriangleTest(gpu, shaders, test);
    RtPipeline pipeline =
        createRtPipeline(gpu, deletion, rt.descriptors.layout, sizeof(ProbePush), shaders);
    const VkBufferUsageFlags usage =
        VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT;
    Buffer rayBuffer =
        createDeviceBuffer(gpu, deletion, rays.data(), rays.size() * sizeof(float), usage);
    Buffer results = createHostBuffer(gpu, deletion, count * sizeof(uint32_t), usage);
    ProbePush push{.rays = rayBuffer.address, .results = results.address, .count = count};
    const uint32_t width = 1024;
    submitOnce(gpu, [&](VkCommandBuffer cmd) {
        recordTrace(cmd, pipeline, rt.descriptors.set, &push, sizeof(push), width,
                    (count + width - 1) / width);
        memoryBarrier(cmd, VK_PIPELINE_STAGE_RAY_TRACING_SHADER_BIT_KHR,
                      VK_ACCESS_SHADER_WRITE_BIT, VK_PIPELINE_STAGE_HOST_BIT,
                      VK_ACCESS_HOST_READ_BIT);
    });
    std::vector<uint32_t> first(count);
    std::memcpy(first.data(), results.mapped, count * sizeof(uint32_t));
    return first;
}

}  // namespace

int main(int argc, char** argv) {
    using namespace rg;
    Options opts;
    int rayCount = 1000000;
    std::vector<std::string> files;
    std::string jsonPath;
    auto extra = [&](CLI::App& app, Options&) {
        app.add_option("--rays", rayCount, "Rays per mesh (half from outside)")
            ->check(CLI::Range(2, 100000000));
        app.add_option("--mesh", files,
                       "A closed mesh file (default: icosphere_3.obj, lens.obj, "
                       "grid_box.obj from bin/assets/meshes)");
        app.add_option("--json", jsonPath, "Also write every count to this file");
    };
    if (auto exit = parseCommandLine(argc, argv, "leak_probe",
                                     "Rays at the edges and vertices of closed meshes: how "
                                     "many pass through, on the GPU and in the reference",
                                     opts, extra))
        return *exit;
    opts.headless = true;
    if (files.empty())
        for (const char* name : {"icosphere_3.obj", "lens.obj", "grid_box.obj"})
            files.push_back((executableDir() / "assets" / "meshes" / name).string());
    return runChapter(opts, [&] {
        App app;
        initApp(app, opts, "leak probe");
        nlohmann::json report = {{"device", app.gpu.physical.properties.deviceName},
                                 {"driver", app.gpu.physical.driver},
                                 {"rays_per_mesh", rayCount}};
        std::printf("rays that passed between triangles\n%-16s %-10s %-22s %-22s\n",
                    "mesh", "test", "from outside", "from inside");
        for (const std::string& file : files) {
            MeshFile loaded = loadMeshFile(file);
            const Mesh& mesh = loaded.meshes.at(0);
            if (mesh.openEdges > 0)
                throw InputError(file + ": not closed (" + std::to_string(mesh.openEdges) +
                                 " open edges): a ray may pass by rights");
            Scene scene = meshAlone(file, mesh);
            std::vector<EdgeRay> aimed = edgeRays(mesh, size_t(rayCount), 12);
            std::vector<float> rays;  // as the GPU gets them: float
            for (const EdgeRay& r : aimed)
                for (const glm::dvec3& v : {r.origin, r.direction})
                    rays.insert(rays.end(), {float(v.x), float(v.y), float(v.z)});
            std::string name = std::filesystem::path(file).filename().string();
            nlohmann::json& entry = report["meshes"][name];
            entry["triangles"] = mesh.indices.size() / 3;
            auto print = [&](const char* test, const Counts* c) {
                std::printf("%-16s %-10s %8llu of %-10llu %8llu of %-10llu\n", name.c_str(),
                            test, (unsigned long long)c[0].through(),
                            (unsigned long long)c[0].rays, (unsigned long long)c[1].through(),
                            (unsigned long long)c[1].rays);
                entry[test] = {{"outside", toJson(c[0])}, {"inside", toJson(c[1])}};
            };
            // The reference, with the same float rays.
            ReferenceRenderer reference(scene);
            Counts counts[2];
            for (size_t i = 0; i < aimed.size(); ++i) {
                glm::dvec3 o(rays[6 * i], rays[6 * i + 1], rays[6 * i + 2]),
                    d(rays[6 * i + 3], rays[6 * i + 4], rays[6 * i + 5]);
                auto hit = ReferenceRenderer::intersectMesh(reference.meshData(0), o, d, 0,
                                                            1e300);
                tally(counts, aimed[i], hit.t < 0 ? 0 : hit.front ? 1 : 2);
            }
            print("reference", counts);
            for (TriangleTest test : {TriangleTest::Builtin, TriangleTest::Watertight}) {
                const char* label = test == TriangleTest::Builtin ? "builtin" : "watertight";
                if (test == TriangleTest::Watertight && !app.gpu.physical.shaderFloat64) {
                    std::printf("%-16s %-10s skipped: no shaderFloat64\n", name.c_str(), label);
                    continue;
                }
                std::vector<uint32_t> first = traceOnGpu(app, scene, rays, test);
                Counts gpuCounts[2];
                for (size_t i = 0; i < aimed.size(); ++i) tally(gpuCounts, aimed[i], first[i]);
                print(label, gpuCounts);
            }
        }
        if (!jsonPath.empty()) {
            std::string text = report.dump(2) + "\n";
            writeFileAtomically(jsonPath, text.data(), text.size());
        }
    });
}
