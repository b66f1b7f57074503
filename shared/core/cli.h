// One command line for every chapter (CLI11). Chapters add their own options
// through the callback; bad input prints one line and gives exit code 2.
#pragma once
#include <cstdint>
#include <functional>
#include <optional>
#include <string>

// Declared ahead: CLI11's header is heavy to compile, so only the files
// that add options include <CLI/CLI.hpp>.
namespace CLI {
class App;
}

namespace rg {

// --numerics: the shaders' branches for huge and tiny scenes (rt_scene.h)
enum class Numerics { Auto, Careful, Fast };

struct Options {
    std::string chapter;          // "04_raygen_miss": names the defaults below
    bool headless = false;        // no window: render offscreen, write PNG and report
    int width = 800;
    int height = 450;
    int frames = 0;               // 0: headless 10, windowed until the window closes
    std::string output;           // PNG path (default out/<chapter>.png)
    std::string report;           // JSON path (default: the PNG path with .json)
    bool validation = false;      // VK_LAYER_KHRONOS_validation + synchronization checks
    int device = -1;              // index into vkEnumeratePhysicalDevices, -1: choose
    // From chapter 03 on:
    std::string scene;            // scene JSON (default: the chapter's own)
    bool reference = false;       // also render the CPU double-precision reference
    // structures built in the scene file's order, not median splits
    bool fileOrder = false;
    // --layout grouped (default, 04 on): static spheres in one BLAS; instances: one each
    bool groupSpheres = true;
    // From chapter 04 on:
    // auto: careful where the scene needs it (rt_scene.h's needsCarefulNumerics)
    Numerics numerics = Numerics::Auto;
    // the window's overlay (viewer.h); --no-ui starts without it
    bool ui = true;
    // the tree whose shaders a window reloads (default: the one built from)
    std::string shaderSource;

    int framesToRun() const { return frames > 0 ? frames : (headless ? 10 : 0); }
};

using ChapterOptions = std::function<void(CLI::App&, Options&)>;

// Parses argv into opts. Returns an exit code when the program should stop
// now (0 after --help, 2 after bad input), std::nullopt to go on.
std::optional<int> parseCommandLine(int argc, char** argv, const std::string& chapter,
                                    const std::string& description, Options& opts,
                                    const ChapterOptions& chapterOptions = {});

// Options every scene chapter (03+) adds: --scene, --file-order; the ray
// tracing chapters (reference=true, 04+) also --reference and --no-ui.
void addSceneOptions(CLI::App& app, Options& opts, bool reference);

// True when a window can be opened (an X11 or Wayland display is set).
bool displayAvailable();

}  // namespace rg
