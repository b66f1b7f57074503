#include "core/cli.h"

#include "core/files.h"

#include <CLI/CLI.hpp>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <utility>
#include <vector>

namespace rg {

bool displayAvailable() {
    const char* x11 = std::getenv("DISPLAY");
    const char* wayland = std::getenv("WAYLAND_DISPLAY");
    return (x11 && *x11) || (wayland && *wayland);
}

void addSceneOptions(CLI::App& app, Options& opts, bool reference) {
    app.add_option("--scene", opts.scene,
                   "Scene JSON file (default: the chapter's own scene)");
    app.add_flag("--file-order", opts.fileOrder,
                 "Build the structures from the objects in the scene file's order "
                 "instead of median splits");
    if (!reference) return;
    app.add_flag("--reference", opts.reference,
                 "Also render the CPU double-precision reference and report the error");
    app.add_flag_callback(
        "--no-ui", [&opts] { opts.ui = false; },
        "Start the window without its overlay (H shows it)");
    app.add_option("--shader-source", opts.shaderSource,
                   "Source tree whose shaders/ are compiled at the start, and again in "
                   "a window when saved or on F5 (default: the build's SPIR-V, and the "
                   "tree built from)")
        ->check(CLI::ExistingDirectory);
    app.add_option("--layout", opts.groupSpheres,
                   "Acceleration structures: grouped (the static spheres in one BLAS of "
                   "boxes, the default) "
                   "or instances (one per object)")
        ->transform(CLI::CheckedTransformer(
            std::map<std::string, bool>{{"instances", false}, {"grouped", true}},
            CLI::ignore_case))
        // --help names the words, not the map behind them
        ->option_text("grouped|instances");
    app.add_option("--numerics", opts.numerics,
                   "The shaders' care for huge and tiny sizes: auto (where the scene "
                   "needs it), careful (always) or fast (never)")
        ->transform(CLI::CheckedTransformer(
            std::map<std::string, Numerics>{{"auto", Numerics::Auto},
                                            {"careful", Numerics::Careful},
                                            {"fast", Numerics::Fast}},
            CLI::ignore_case))
        ->option_text("auto|careful|fast");
}

namespace {

// A run must not write over its own input: a report named after the scene
// file (--output floor.png next to floor.json) would replace the scene.
std::optional<std::string> outputClash(const Options& opts) {
    namespace fs = std::filesystem;
    auto canonical = [](const fs::path& p) {
        std::error_code ec;
        fs::path c = fs::weakly_canonical(p, ec);
        return ec ? p.lexically_normal() : c;
    };
    fs::path png = opts.output, stem = png.parent_path() / png.stem();
    if (canonical(png) == canonical(opts.report))
        return "--output and --report name the same file " + opts.output;
    if (opts.scene.empty()) return std::nullopt;
    std::vector<std::pair<std::string, fs::path>> written = {
        {"--output", png},
        {"--report", opts.report},
        {"the image's copy", fs::path(png).replace_extension(".pfm")}};
    if (opts.reference)
        for (const char* suffix : {"_reference.png", "_reference.pfm", "_error.png"})
            written.push_back({"the reference's output", stem.string() + suffix});
    for (const auto& [what, path] : written)
        if (canonical(path) == canonical(opts.scene))
            return what + " " + path.string() + " would overwrite the scene file " +
                   opts.scene + "; choose another --output or --report";
    return std::nullopt;
}

}  // namespace

std::optional<int> parseCommandLine(int argc, char** argv, const std::string& chapter,
                                    const std::string& description, Options& opts,
                                    const ChapterOptions& chapterOptions) {
    opts.chapter = chapter;
    CLI::App app{description, chapter};
    app.add_flag("--headless", opts.headless,
                 "Render offscreen (default when no display exists)");
    app.add_option("--width", opts.width, "Image width in pixels")
        ->check(CLI::Range(1, 16384));
    app.add_option("--height", opts.height, "Image height in pixels")
        ->check(CLI::Range(1, 16384));
    app.add_option("--frames", opts.frames,
                   "Frames to render (default: 10 headless, until closed in a window)")
        ->check(CLI::Range(1, 1000000));
    app.add_option("--output", opts.output, "PNG to write (default: out/<chapter>.png)");
    app.add_option("--report", opts.report,
                   "JSON report to write (default: the PNG name with .json)");
    app.add_flag(
        "--validation", opts.validation,
        "Enable the Khronos validation layer; any message makes the exit code non-zero");
    app.add_option("--device", opts.device,
                   "Physical device index to use (see the list printed at start)")
        ->check(CLI::Range(0, 64));
    if (chapterOptions) chapterOptions(app, opts);

    try {
        app.parse(argc, argv);
    } catch (const CLI::CallForHelp&) {
        std::printf("%s", app.help().c_str());
        return 0;
    } catch (const CLI::ParseError& e) {
        std::fprintf(stderr, "%s: error: %s (see --help)\n", chapter.c_str(),
                     escapeControl(e.what()).c_str());
        return 2;
    }
    if (!opts.headless && !displayAvailable()) opts.headless = true;
    // Outputs go to out/ (from where the chapter runs) unless --output says
    // otherwise, never beside the sources; the folder is made when missing.
    if (opts.output.empty()) opts.output = "out/" + chapter + ".png";
    if (opts.report.empty())
        opts.report =
            std::filesystem::path(opts.output).replace_extension(".json").string();
    if (auto clash = outputClash(opts)) {
        std::fprintf(stderr, "%s: error: %s\n", chapter.c_str(), clash->c_str());
        return 2;
    }
    for (const std::string& file : {opts.output, opts.report}) {
        std::filesystem::path folder = std::filesystem::path(file).parent_path();
        std::error_code error;
        if (folder.empty() || std::filesystem::is_directory(folder, error)) continue;
        std::filesystem::create_directories(folder, error);
        if (error) {
            std::fprintf(stderr, "%s: error: cannot make the folder %s for %s: %s\n",
                         chapter.c_str(), escapeControl(folder.string()).c_str(),
                         escapeControl(file).c_str(), error.message().c_str());
            return 2;
        }
    }
    return std::nullopt;
}

}  // namespace rg
