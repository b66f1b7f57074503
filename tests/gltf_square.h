// Chapter 12's tests: one run of the chapter, and a glTF file of one
// textured square, written by the test itself (a .gltf and its .bin beside
// the PNGs it names).
#pragma once
#include "harness.h"

#include <glm/glm.hpp>
#include <nlohmann/json.hpp>

#include <cstdint>
#include <fstream>
#include <string>
#include <utility>
#include <vector>

namespace {

// Runs chapter 12 on `scene` (160 x 90, one frame, validation on) into `png`.
inline rgtest::Png render(const std::string& scene, const std::string& png,
                          const std::vector<std::string>& extra = {}) {
    std::vector<std::string> args = {"--headless", "--validation", "--scene", scene, "--width", "160",
                                     "--height", "90", "--frames", "1", "--output", png};
    args.insert(args.end(), extra.begin(), extra.end());
    rgtest::RunResult r = rgtest::run(RG_EXE_12, args);
    EXPECT_EQ(r.exitCode, 0) << r.output;
    EXPECT_EQ(r.output.find("Validation"), std::string::npos) << r.output;
    return rgtest::readPng(png);
}

struct Square {
    glm::vec3 corners[4];  // counter-clockwise seen from its front
    glm::vec2 uv[4];
};

// The square [-1, 1]^2 scaled by `size` in the plane z = 0, facing +z, its
// texture's u along +x (or -x, `mirrored`) and the image's top at +y.
inline Square wall(float size, bool mirrored = false) {
    float u0 = mirrored ? 1.0f : 0.0f, u1 = 1.0f - u0;
    return {{{-size, -size, 0}, {size, -size, 0}, {size, size, 0}, {-size, size, 0}},
            {{u0, 1}, {u1, 1}, {u1, 0}, {u0, 0}}};
}

// A glTF file of one square with `material`, whose textures are the PNGs
// named in `textures` ({slot, file}: "normalTexture" on the material, the
// others in pbrMetallicRoughness), each through `sampler` where one is given.
inline void writeSquareGltf(const std::string& dir, const std::string& name, const Square& s, nlohmann::json material,
                            const std::vector<std::pair<std::string, std::string>>& textures,
                            const nlohmann::json& sampler = nullptr) {
    struct Data {
        float xyz[12];
        float uv[8];
        uint32_t indices[6] = {0, 1, 2, 0, 2, 3};
    } data{};
    for (int i = 0; i < 4; ++i) {
        for (int c = 0; c < 3; ++c) data.xyz[3 * i + c] = s.corners[i][c];
        data.uv[2 * i] = s.uv[i].x, data.uv[2 * i + 1] = s.uv[i].y;
    }
    std::ofstream(dir + "/" + name + ".bin", std::ios::binary)
        << std::string(reinterpret_cast<const char*>(&data), sizeof data);
    nlohmann::json j = {
        {"asset", {{"version", "2.0"}}}, {"scene", 0}, {"scenes", {{{"nodes", {0}}}}}, {"nodes", {{{"mesh", 0}}}},
        {"meshes", {{{"primitives", {{{"attributes", {{"POSITION", 0}, {"TEXCOORD_0", 1}}}, {"indices", 2}, {"material", 0}}}}}}},
        {"buffers", {{{"uri", name + ".bin"}, {"byteLength", sizeof data}}}},
        {"bufferViews", {{{"buffer", 0}, {"byteOffset", 0}, {"byteLength", 48}},
                         {{"buffer", 0}, {"byteOffset", 48}, {"byteLength", 32}},
                         {{"buffer", 0}, {"byteOffset", 80}, {"byteLength", 24}}}},
        {"accessors", {{{"bufferView", 0}, {"componentType", 5126}, {"count", 4}, {"type", "VEC3"}},
                       {{"bufferView", 1}, {"componentType", 5126}, {"count", 4}, {"type", "VEC2"}},
                       {{"bufferView", 2}, {"componentType", 5125}, {"count", 6}, {"type", "SCALAR"}}}}};
    for (size_t i = 0; i < textures.size(); ++i) {
        j["images"].push_back({{"uri", textures[i].second}});
        j["textures"].push_back({{"source", i}});
        if (!sampler.is_null()) j["textures"].back()["sampler"] = 0;
        nlohmann::json& owner = textures[i].first == "normalTexture" ? material : material["pbrMetallicRoughness"];
        owner[textures[i].first]["index"] = i;
    }
    j["materials"] = {material};
    if (!sampler.is_null()) j["samplers"] = {sampler};
    std::ofstream(dir + "/" + name + ".gltf", std::ios::binary) << j.dump();
}

}  // namespace
