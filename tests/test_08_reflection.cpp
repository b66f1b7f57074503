// Chapter 08: the depth limit. Between two perfect facing mirrors every path
// reaches it; a deeper limit traces more rays (counted) and shows more
// reflections, and the reference agrees at every depth.
#include "harness.h"

namespace {

TEST(Chapter08, DepthLimitBetweenFacingMirrors) {
    std::string scene = RG_SOURCE_DIR "/tests/scenes/mirrors_depth_limit.json";
    long previousRays = 0;
    for (int depth : {0, 2, 8}) {
        nlohmann::json report = rgtest::expectMatchesReference(RG_EXE_08, scene, "08_depth_" + std::to_string(depth),
                                                               {"--depth", std::to_string(depth)});
        long rays = report.value("rays_per_frame", 0L);
        EXPECT_GT(rays, previousRays) << "depth " << depth;
        previousRays = rays;
    }
}

TEST(Chapter08, DepthOutOfRangeIsRejected) {
    rgtest::RunResult r = rgtest::run(RG_EXE_08, {"--headless", "--depth", "9"});
    EXPECT_EQ(r.exitCode, 2) << r.output;
    EXPECT_NE(r.output.find("--depth"), std::string::npos);
}

}  // namespace
