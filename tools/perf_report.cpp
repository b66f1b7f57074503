// The speed-versus-error report (issue: chapter 11 and the performance page).
// Runs the built chapters on whatever Vulkan device there is and writes, into
// --out: perf.json (every number), perf.md (the tables), convergence.dat (for
// the plots). Needs only the chapter executables beside it, so it runs on a
// machine without jq or gnuplot; tools/perf-report.sh makes the plots.
#include "core/files.h"
#include "core/image.h"
#include "reference/reference.h"
#include "scene/scene.h"

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

std::string binDir, outDir;

json runChapter(const std::string& name, const std::vector<std::string>& args, const std::string& tag) {
    std::string png = outDir + "/runs/" + tag + ".png";
    std::string command = "'" + binDir + "/" + name + "' --headless --output '" + png + "'";
    for (const auto& a : args) command += " '" + a + "'";
    command += " > '" + outDir + "/runs/" + tag + ".log' 2>&1";
    std::printf("  %-60s", (name + " " + tag).c_str());
    std::fflush(stdout);
    int status = std::system(command.c_str());
    std::ifstream file(fs::path(png).replace_extension(".json"));
    json report = file ? json::parse(file, nullptr, false) : json();
    if (status != 0 || report.is_discarded() || report.is_null()) {
        std::printf("FAILED (see runs/%s.log)\n", tag.c_str());
        return json();
    }
    std::printf("%8.3f ms\n", report["gpu_ms"].value("median", 0.0));
    if (report.contains("scene"))  // its file name: docs/perf/ keeps no path of the measuring machine
        report["scene"] = fs::path(report["scene"].get<std::string>()).filename().string();
    return report;
}

std::string fmt(const char* f, double v) {
    char b[64];
    std::snprintf(b, sizeof b, f, v);
    return b;
}

// Least-squares slope of log(y) against log(x).
double logSlope(const std::vector<double>& x, const std::vector<double>& y) {
    double n = double(x.size()), sx = 0, sy = 0, sxx = 0, sxy = 0;
    for (size_t i = 0; i < x.size(); ++i) {
        double lx = std::log(x[i]), ly = std::log(y[i]);
        sx += lx, sy += ly, sxx += lx * lx, sxy += lx * ly;
    }
    return (n * sxy - sx * sy) / (n * sxx - sx * sx);
}

// log-log interpolation of y(x) at x0 (clamped to the measured range).
double logInterpolate(const std::vector<double>& x, const std::vector<double>& y, double x0) {
    if (x0 <= x.front()) return y.front();
    for (size_t i = 1; i < x.size(); ++i)
        if (x0 <= x[i]) {
            double t = (std::log(x0) - std::log(x[i - 1])) / (std::log(x[i]) - std::log(x[i - 1]));
            return std::exp(std::log(y[i - 1]) + t * (std::log(y[i]) - std::log(y[i - 1])));
        }
    return y.back();
}

}  // namespace

int report(int argc, char** argv);

int main(int argc, char** argv) {
    try {
        return report(argc, argv);
    } catch (const std::exception& e) {  // a chapter that failed leaves no image to compare: say so, once
        std::fprintf(stderr, "perf_report: %s\n", e.what());
        return 1;
    }
}

int report(int argc, char** argv) {
    CLI::App app{"RayGlass speed-versus-error report"};
    int width = 640, height = 360, frames = 20, studyWidth = 160, studyHeight = 90, studyFrames = 5;
    int referenceSamples = 65536, maxAccumulated = 1024, studyRounds = 3;
    app.add_option("--bin", binDir, "Folder of the chapter executables")->required();
    app.add_option("--out", outDir, "Folder for the results")->required();
    app.add_option("--width", width)->capture_default_str();
    app.add_option("--height", height)->capture_default_str();
    app.add_option("--frames", frames, "Frames per timing run")->capture_default_str();
    app.add_option("--study-width", studyWidth, "Chapter 11 convergence study size")->capture_default_str();
    app.add_option("--study-height", studyHeight)->capture_default_str();
    app.add_option("--study-frames", studyFrames)->capture_default_str();
    app.add_option("--study-rounds", studyRounds, "Rounds of the timed one-frame runs (the fastest counts)")
        ->check(CLI::Range(1, 100))
        ->capture_default_str();
    app.add_option("--reference-samples", referenceSamples, "Per rough hit, in each of the two CPU references")
        ->capture_default_str();
    app.add_option("--max-accumulated", maxAccumulated, "Longest accumulation of the progressive study (frames)")
        ->capture_default_str();
    CLI11_PARSE(app, argc, argv);
    fs::create_directories(outDir + "/runs");
    const std::string scenes = binDir + "/assets/scenes/";
    const std::string W = std::to_string(width), H = std::to_string(height), F = std::to_string(frames);
    json data;
    char date[32];
    std::time_t now = std::time(nullptr);
    std::strftime(date, sizeof date, "%Y-%m-%d", std::gmtime(&now));
    data["date"] = date;

    std::printf("1/4 every chapter at %dx%d, %d frames\n", width, height, frames);
    const char* chapters[] = {"03_acceleration_structures", "04_raygen_miss", "05_ambient", "06_diffuse",
                              "07_specular", "08_reflection", "09_fresnel", "10_refraction", "11_rough"};
    for (const char* c : chapters) {
        std::vector<std::string> args = {"--width", W, "--height", H, "--frames", F};
        json r;
        if (std::string(c) == "11_rough") {
            json one = runChapter(c, {"--width", W, "--height", H, "--frames", F, "--samples", "1"}, "11_rough_1spp");
            if (!one.is_null()) one["label"] = "11_rough (1 sample per hit, progressive)";
            if (!one.is_null()) data["chapters"].push_back(one);
            args.insert(args.end(), {"--samples", "25", "--no-accumulate"});
            r = runChapter(c, args, "11_rough_25spp");
            if (!r.is_null()) r["label"] = "11_rough (25 samples per hit)";
        } else {
            r = runChapter(c, args, c);
        }
        if (!r.is_null()) data["chapters"].push_back(r);
        if (!r.is_null()) data["device"] = r["device"], data["driver"] = r["driver"];
    }

    std::printf("2/4 chapter 11 convergence at %dx%d (scene rough.json)\n", studyWidth, studyHeight);
    const std::string SW = std::to_string(studyWidth), SH = std::to_string(studyHeight);
    // The converged reference: the mean of two CPU renders with independent
    // seeds. Their difference measures the error honestly (stratified
    // samples beat the independent-sample formula): each has error e, the
    // difference sqrt(2) e, the mean e / sqrt(2) = RMS(difference) / 2.
    auto converged = [&](const std::string& sceneFile, int samples, double& error) {
        rg::Scene scene = rg::toCameraSpace(rg::loadScene(scenes + sceneFile));  // as chapter 11 sees it
        rg::ReferenceRenderer renderer(scene);
        rg::ReferenceSettings settings{.stage = rg::ReferenceStage::Rough, .maxDepth = 4, .fresnelMode = 0,
                                       .samples = samples};
        auto start = std::chrono::steady_clock::now();
        settings.seed = 1;
        rg::FloatImage a = renderer.render(settings, studyWidth, studyHeight);
        settings.seed = 2;
        rg::FloatImage b = renderer.render(settings, studyWidth, studyHeight);
        error = rg::compareImages(a, b, nullptr).rmse / 2;
        for (size_t k = 0; k < a.rgba.size(); ++k) a.rgba[k] = 0.5f * (a.rgba[k] + b.rgba[k]);
        double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        std::printf("  reference %s: 2 x %d stratified samples per rough hit, %.1f s, its RMS error %.2e\n",
                    sceneFile.c_str(), samples, seconds, error);
        return a;
    };
    double referenceError = 0;
    rg::FloatImage reference = converged("rough.json", referenceSamples, referenceError);
    data["study"] = {{"width", studyWidth}, {"height", studyHeight}, {"frames", studyFrames},
                     {"reference_samples", 2 * referenceSamples}, {"reference_error_rms", referenceError}};
    auto rmseOf = [&](const std::string& tag, const rg::FloatImage& against) {
        return rg::compareImages(rg::readPfm(outDir + "/runs/" + tag + ".pfm"), against, nullptr).rmse;
    };
    const char* patterns[] = {"uniform", "stratified", "hammersley", "sobol"};
    std::ostringstream dat;  // each output written whole at the end (files.h)
    auto& P = data["study"]["patterns"];

    // Progressive: one sample per hit and frame, accumulated over 1 ... 1024
    // frames; the slope is fitted from 16 samples on.
    dat << "# accumulated: pattern samples rmse (blocks 0-3)\n";
    for (const char* p : patterns) {
        std::vector<double> n, err, nFit, errFit;
        for (int frames = 1; frames <= maxAccumulated; frames *= 2) {
            std::string tag = std::string("11_acc_") + p + "_" + std::to_string(frames);
            json r = runChapter("11_rough", {"--scene", scenes + "rough.json", "--width", SW, "--height", SH,
                                             "--frames", std::to_string(frames), "--samples", "1", "--pattern", p},
                                tag);
            if (r.is_null()) continue;
            n.push_back(frames), err.push_back(rmseOf(tag, reference));
            if (frames >= 16) nFit.push_back(n.back()), errFit.push_back(err.back());
            dat << p << " " << frames << " " << err.back() << "\n";
        }
        P[p]["accumulated"] = {{"samples", n}, {"rmse", err}, {"slope_16_up", nFit.size() > 1 ? logSlope(nFit, errFit) : 0.0}};
        dat << "\n\n";
    }

    // One frame of N samples per hit, timed: RMSE against samples and time,
    // then each pattern's RMSE at the GPU times of uniform's runs.
    const int counts[] = {1, 4, 9, 16, 25, 64, 100};
    auto oneFrame = [&](const std::string& sceneFile, const std::string& tagPrefix, const rg::FloatImage& against,
                        json& out) {
        auto run = [&](const char* p, int c, const std::string& tag) {
            return runChapter("11_rough", {"--scene", scenes + sceneFile, "--width", SW, "--height", SH, "--frames",
                                           std::to_string(studyFrames), "--samples", std::to_string(c), "--pattern",
                                           p, "--no-accumulate"}, tag);
        };
        run("uniform", 1, tagPrefix + "warm_up");  // not counted: the first run after the CPU reference is slower
        // Rounds of every count, the patterns in turn at each, so that a
        // machine's drift falls on all of them alike; each keeps its fastest
        // frame over the rounds: on a CPU shared with other work (lavapipe)
        // interference only ever adds time. The images do not change.
        std::map<std::string, std::vector<double>> fastest;
        for (int round = 0; round < studyRounds; ++round)
            for (size_t i = 0; i < std::size(counts); ++i)
                for (const char* p : patterns) {
                    std::string tag = tagPrefix + p + "_" + std::to_string(counts[i]);
                    json r = run(p, counts[i], tag);
                    double ms = r.is_null() ? INFINITY : r["gpu_ms"].value("min", 0.0);
                    auto& f = fastest[p];
                    if (f.size() <= i) f.push_back(ms);
                    else f[i] = std::min(f[i], ms);
                }
        for (const char* p : patterns) {
            out[p]["samples"] = json::array(), out[p]["gpu_ms"] = json::array(), out[p]["rmse"] = json::array();
            for (size_t i = 0; i < std::size(counts); ++i) {
                if (!std::isfinite(fastest[p][i])) continue;  // failed in every round
                out[p]["samples"].push_back(counts[i]), out[p]["gpu_ms"].push_back(fastest[p][i]);
                out[p]["rmse"].push_back(rmseOf(tagPrefix + p + "_" + std::to_string(counts[i]), against));
            }
            std::vector<double> n = out[p]["samples"], err = out[p]["rmse"];
            out[p]["slope"] = n.size() > 1 ? logSlope(n, err) : 0.0;
        }
        std::vector<double> uMs = out["uniform"]["gpu_ms"], uErr = out["uniform"]["rmse"];
        for (const char* p : {"stratified", "hammersley", "sobol"}) {
            std::vector<double> ms = out[p]["gpu_ms"], err = out[p]["rmse"];
            std::vector<double> ratios;
            for (size_t i = 0; i < uMs.size() && !ms.empty(); ++i)
                ratios.push_back(logInterpolate(ms, err, uMs[i]) / uErr[i]);
            out[p]["equal_time_ratio_to_uniform"] = ratios;
        }
    };
    oneFrame("rough.json", "11_", reference, P);
    dat << "# one frame: pattern samples gpu_ms rmse (blocks 4-7)\n";
    for (const char* p : patterns) {
        for (size_t i = 0; i < P[p]["samples"].size(); ++i)
            dat << p << " " << P[p]["samples"][i].get<double>() << " " << P[p]["gpu_ms"][i].get<double>() << " "
                << P[p]["rmse"][i].get<double>() << "\n";
        dat << "\n\n";
    }
    // The same on a smooth integrand (rough_sky.json: no edge in any lobe),
    // where stratification does what it cannot do across an edge.
    int smoothSamples = std::min(referenceSamples, 16384);  // smooth: far fewer suffice
    double smoothError = 0;
    rg::FloatImage smoothReference = converged("rough_sky.json", smoothSamples, smoothError);
    json& S = data["study"]["smooth"];
    S = {{"scene", "rough_sky.json"}, {"reference_samples", 2 * smoothSamples}, {"reference_error_rms", smoothError}};
    oneFrame("rough_sky.json", "11_sky_", smoothReference, S["patterns"]);

    std::printf("3/4 Fresnel: Schlick against exact on glass_sphere.json\n");
    json fresnel;
    for (const char* mode : {"schlick-ior", "exact"}) {
        json r = runChapter("10_refraction", {"--scene", scenes + "glass_sphere.json", "--width", W, "--height", H,
                                              "--frames", F, "--fresnel", mode}, std::string("10_fresnel_") + mode);
        fresnel[mode] = r.is_null() ? json() : r["gpu_ms"];
    }
    rg::ImageError fe = rg::compareImages(rg::readPfm(outDir + "/runs/10_fresnel_schlick-ior.pfm"),
                                          rg::readPfm(outDir + "/runs/10_fresnel_exact.pfm"), nullptr);
    fresnel["image_rmse"] = fe.rmse;
    fresnel["image_frac_over_1_255"] = fe.fracOver1_255;
    data["fresnel"] = fresnel;

    std::printf("4/4 sphere model: analytic against icospheres, chapter 10 on glass_sphere.json\n");
    json analytic = runChapter("10_refraction", {"--scene", scenes + "glass_sphere.json", "--width", W, "--height", H,
                                                 "--frames", F, "--reference"}, "10_mesh_0");
    rg::FloatImage sphereReference = rg::readPfm(outDir + "/runs/10_mesh_0_reference.pfm");
    for (int level = 0; level <= 5; ++level) {
        std::string tag = "10_mesh_" + std::to_string(level);
        json r = level == 0 ? analytic
                            : runChapter("10_refraction", {"--scene", scenes + "glass_sphere.json", "--width", W,
                                                           "--height", H, "--frames", F, "--sphere-mesh",
                                                           std::to_string(level)}, tag);
        if (r.is_null()) continue;
        rg::ImageError e = rg::compareImages(rg::readPfm(outDir + "/runs/" + tag + ".pfm"), sphereReference, nullptr);
        data["sphere_model"].push_back({{"level", level}, {"triangles", level == 0 ? 0 : 20 * (1 << (2 * level))},
                                        {"gpu_ms", r["gpu_ms"].value("median", 0.0)}, {"rmse", e.rmse},
                                        {"frac_over_1_255", e.fracOver1_255}});
    }
    std::string perfJson = data.dump(2) + "\n";

    // The tables.
    std::ostringstream md;
    md << "### " << data.value("device", "?") << "\n\n"
       << "Driver: " << data.value("driver", "?") << ". Measured " << data["date"].get<std::string>()
       << " with `tools/perf-report.sh`. GPU times are medians of timestamp queries.\n\n"
       << "**Every chapter** at " << width << "x" << height << ", " << frames << " frames:\n\n"
       << "| chapter | median ms | min ms | max ms | rays per frame | Mrays/s |\n| --- | --- | --- | --- | --- | --- |\n";
    for (const auto& r : data["chapters"]) {
        std::string name = r.value("label", r.value("chapter", ""));
        md << "| " << name << " | " << fmt("%.3f", r["gpu_ms"].value("median", 0.0)) << " | "
           << fmt("%.3f", r["gpu_ms"].value("min", 0.0)) << " | " << fmt("%.3f", r["gpu_ms"].value("max", 0.0)) << " | "
           << (r.contains("rays_per_frame") ? std::to_string(r["rays_per_frame"].get<long>()) : "-") << " | "
           << (r.contains("mrays_per_s") ? fmt("%.1f", r["mrays_per_s"].get<double>()) : "-") << " |\n";
    }
    md << "\n**Chapter 11 against the converged reference** (scene `rough.json`, " << studyWidth << "x" << studyHeight
       << "; reference: the mean of two CPU renders of " << referenceSamples
       << " stratified samples per rough hit with independent seeds, its RMS error measured from their difference: "
       << fmt("%.1e", referenceError) << ").\n\n"
       << "*Progressive*, one sample per hit and frame, RMSE after N accumulated frames:\n\n| pattern |";
    for (double n : P["sobol"]["accumulated"]["samples"]) md << " " << n << " |";
    md << " slope (16 up) |\n| --- |";
    for (size_t i = 0; i < P["sobol"]["accumulated"]["samples"].size(); ++i) md << " --- |";
    md << " --- |\n";
    for (const char* p : patterns) {
        md << "| " << p << " |";
        for (double e : P[p]["accumulated"]["rmse"]) md << " " << fmt("%.2e", e) << " |";
        md << " " << fmt("%.2f", P[p]["accumulated"]["slope_16_up"].get<double>()) << " |\n";
    }
    md << "\n*One frame of N samples per hit* (GPU time: the fastest of " << studyFrames << " frames in each of " << studyRounds << " rounds):\n\n"
       << "| pattern | samples | GPU ms | RMSE |\n| --- | --- | --- | --- |\n";
    for (const char* p : patterns)
        for (size_t i = 0; i < P[p]["samples"].size(); ++i)
            md << "| " << p << " | " << P[p]["samples"][i].get<double>() << " | "
               << fmt("%.3f", P[p]["gpu_ms"][i].get<double>()) << " | " << fmt("%.2e", P[p]["rmse"][i].get<double>())
               << " |\n";
    md << "\nLog-log slope of RMSE against samples in one frame (-0.5 is independent random sampling):";
    for (const char* p : patterns) md << " " << p << " " << fmt("%.2f", P[p]["slope"].get<double>()) << ";";
    // Uniform's sample counts as measured, then each pattern's RMSE relative
    // to uniform's at those counts' times.
    auto uniformCounts = [](const json& patterns) {
        std::string list;
        for (const auto& n : patterns["uniform"]["samples"]) list += (list.empty() ? "" : ", ") + n.dump();
        return list;
    };
    auto equalTimeRatios = [&](const json& patterns) {
        for (const char* p : {"stratified", "hammersley", "sobol"}) {
            md << "- " << p << ":";
            for (double r : patterns[p]["equal_time_ratio_to_uniform"]) md << " " << fmt("%.2f", r);
            md << "\n";
        }
    };
    md << "\n\nAt equal GPU time, RMSE relative to uniform random (at uniform's times for " << uniformCounts(P)
       << " samples):\n\n";
    equalTimeRatios(P);
    const json& SP = data["study"]["smooth"]["patterns"];
    md << "\nThe same on a smooth integrand (`rough_sky.json`, a rough mirror that reflects only the sky's gradient; "
       << "reference: 2 x " << smoothSamples << " samples, its RMS error " << fmt("%.1e", smoothError)
       << "). RMSE of uniform random at " << uniformCounts(SP) << " samples:";
    for (double e : SP["uniform"]["rmse"]) md << " " << fmt("%.2e", e);
    md << "; the others relative to it at equal GPU time:\n\n";
    equalTimeRatios(SP);
    md << "\n**Fresnel** (chapter 10, `glass_sphere.json`, " << width << "x" << height << "): Schlick with f0 from the "
       << "IOR " << fmt("%.3f", fresnel["schlick-ior"].value("median", 0.0)) << " ms, exact "
       << fmt("%.3f", fresnel["exact"].value("median", 0.0)) << " ms; the two images differ by RMSE "
       << fmt("%.2e", fe.rmse) << ", " << fmt("%.2f", 100 * fe.fracOver1_255) << " % of pixels by more than 1/255.\n";
    md << "\n**Sphere model** (chapter 10, `glass_sphere.json`, " << width << "x" << height
       << ", error against the analytic sphere's CPU reference; icospheres with interpolated normals):\n\n"
       << "| sphere | triangles | GPU ms | RMSE | pixels off by > 1/255 |\n| --- | --- | --- | --- | --- |\n";
    for (const auto& m : data["sphere_model"]) {
        int level = m["level"];
        md << "| " << (level == 0 ? std::string("analytic (AABB + intersection shader)") : "icosphere level " + std::to_string(level))
           << " | " << (level == 0 ? std::string("-") : std::to_string(m["triangles"].get<int>())) << " | "
           << fmt("%.3f", m["gpu_ms"].get<double>()) << " | " << fmt("%.2e", m["rmse"].get<double>()) << " | "
           << fmt("%.2f", 100 * m["frac_over_1_255"].get<double>()) << " % |\n";
    }
    auto write = [&](const std::string& name, const std::string& text) {
        rg::writeFileAtomically(outDir + "/" + name, text.data(), text.size());
    };
    write("perf.json", perfJson);
    write("perf.md", md.str());
    write("convergence.dat", dat.str());
    std::printf("wrote %s/perf.json, perf.md, convergence.dat\n", outDir.c_str());
    return 0;
}
