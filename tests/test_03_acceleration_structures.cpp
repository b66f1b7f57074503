// Chapter 03: the statistics agree with the scene (one instance per object,
// non-zero sizes, compaction never grows a BLAS), and the top view drawn from
// the TLAS's instance buffer shows each instance where the host put it,
// including the moving one after the last frame's refit.
#include "harness.h"

#include "host_device.h"

#include <fstream>

namespace {

glm::vec3 expectedColor(uint32_t i) { return rg::gpu::instanceColor(i); }

TEST(Chapter03, StatisticsMatchTheSceneAndTheTopViewShowsEveryInstance) {
    const int w = 320, h = 180, frames = 60;  // as page 03: the moving sphere at its farthest, clear of the others
    std::string dir = rgtest::outputDir("03");
    rgtest::RunResult r = rgtest::run(RG_EXE_03, {"--headless", "--validation", "--width", std::to_string(w),
                                                  "--height", std::to_string(h), "--frames", std::to_string(frames),
                                                  "--output", dir + "/03.png"});
    ASSERT_EQ(r.exitCode, 0) << r.output;
    nlohmann::json report = rgtest::readJson(dir + "/03.json");
    rgtest::expectCleanReport(report, "03_acceleration_structures", w, h);

    std::ifstream sceneFile(RG_SOURCE_DIR "/assets/scenes/default.json");
    nlohmann::json scene = nlohmann::json::parse(sceneFile);
    size_t objects = scene["objects"].size();
    EXPECT_EQ(report["tlas"].value("instances", 0u), objects);
    EXPECT_GT(report["tlas"].value("size_bytes", 0u), 0u);
    ASSERT_EQ(report["blas"].size(), 2u);
    for (const auto& blas : report["blas"]) {
        EXPECT_GT(blas.value("size_bytes", 0u), 0u);
        EXPECT_GT(blas.value("compacted_bytes", 0u), 0u);
        EXPECT_LE(blas.value("compacted_bytes", 0u), blas.value("size_bytes", 0u));
    }
    EXPECT_EQ(report["top_view"].value("last_frame", 0), frames - 1);
    EXPECT_GT(report["tlas"].value("update_ms", 0.0), 0.0);  // the refit, timed on its own

    // Every instance shows: somewhere in its box (a 7 x 7 grid of points inside its outline),
    // no smaller box covers it, and there the top view has its colour. The
    // moving one shows away from where the scene file puts it.
    rgtest::Png png = rgtest::readPng(dir + "/03.png");
    ASSERT_EQ(png.width, w);
    const auto& view = report["top_view"];
    const auto& instances = report["instances"];
    ASSERT_EQ(instances.size(), objects);
    auto box = [&](size_t j, int k, int axis) { return instances[j][k ? "box_max_xz" : "box_min_xz"][axis].get<double>(); };
    auto smallestCovering = [&](double x, double z) {
        size_t top = instances.size();
        double smallest = 1e300;
        for (size_t j = 0; j < instances.size(); ++j) {
            double area = (box(j, 1, 0) - box(j, 0, 0)) * (box(j, 1, 1) - box(j, 0, 1));
            if (x >= box(j, 0, 0) && x <= box(j, 1, 0) && z >= box(j, 0, 1) && z <= box(j, 1, 1) && area < smallest)
                top = j, smallest = area;
        }
        return top;
    };
    int moving = 0;
    for (size_t i = 0; i < instances.size(); ++i) {
        bool shown = false;
        for (int gy = 2; gy < 9 && !shown; ++gy)  // inside its outline
            for (int gx = 2; gx < 9 && !shown; ++gx) {
                double x = box(i, 0, 0) + (box(i, 1, 0) - box(i, 0, 0)) * gx / 10.0;
                double z = box(i, 0, 1) + (box(i, 1, 1) - box(i, 0, 1)) * gy / 10.0;
                if (smallestCovering(x, z) != i) continue;
                int px = int((x - view["x0"].get<double>()) / view["width"].get<double>() * w);
                int py = int((z - view["z0"].get<double>()) / view["depth"].get<double>() * h);
                ASSERT_TRUE(px >= 0 && px < w && py >= 0 && py < h);
                glm::vec3 want = expectedColor(instances[i]["object"].get<uint32_t>());  // coloured by object
                const uint8_t* p = png.at(px, py);
                EXPECT_NEAR(p[0], rgtest::display8(want.r), 1) << "instance " << i;
                EXPECT_NEAR(p[1], rgtest::display8(want.g), 1) << "instance " << i;
                EXPECT_NEAR(p[2], rgtest::display8(want.b), 1) << "instance " << i;
                shown = true;
            }
        EXPECT_TRUE(shown) << "instance " << i << " is hidden under smaller boxes";
        if (instances[i].value("moving", false)) {
            ++moving;
            double start = scene["objects"][instances[i]["object"].get<size_t>()]["center"][0].get<double>();
            EXPECT_GT(std::abs(0.5 * (box(i, 0, 0) + box(i, 1, 0)) - start), 0.4) << "the moving instance did not move";
        }
    }
    EXPECT_EQ(moving, 1);
}

// Moving one of many instances: only its 64 bytes are sent, so a TLAS of
// any size refits (vkCmdUpdateBuffer takes at most 64 KiB, 1024 instances).
TEST(Chapter03, OneMovingSphereAmongThousandsRefits) {
    std::string dir = rgtest::outputDir("03_many");
    std::ofstream scene(dir + "/many.json");
    scene << R"({"camera": {}, "materials": {"m": {}}, "objects": [)";
    for (int i = 0; i < 3000; ++i)
        scene << (i ? "," : "") << R"({"type": "sphere", "radius": 0.4, "material": "m", "center": [)" << i % 60
              << ", 0, " << i / 60 << "]" << (i == 1234 ? R"(, "moving": true})" : "}");
    scene << "]}";
    scene.close();
    rgtest::RunResult r = rgtest::run(RG_EXE_03, {"--headless", "--validation", "--width", "64", "--height", "36",
                                                  "--frames", "4", "--scene", dir + "/many.json",
                                                  "--output", dir + "/many_render.png"});
    ASSERT_EQ(r.exitCode, 0) << r.output;
    nlohmann::json report = rgtest::readJson(dir + "/many_render.json");
    EXPECT_EQ(report["tlas"].value("instances", 0u), 3000u);
    EXPECT_GT(report["tlas"].value("update_ms", 0.0), 0.0);
    EXPECT_EQ(report.value("validation_messages", -1), 0);
}

TEST(Chapter03Windowed, RefitsAndPresentsUnderXvfb) {
    rgtest::expectCleanWindowedRun(RG_EXE_03, "03_window", 20);
}

}  // namespace
