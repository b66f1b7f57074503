// Optics read off a chapter's own images (chapters 12 and 13). The sky says
// where each pixel's ray went: its red channel climbs through all 256 codes
// across a band of the sky (rows for the lens, columns for the prism), its
// green is 255 there and every other direction is black. Filtering is
// linear between texel centres, so red / green inverts exactly to a texel
// position and so to a direction; Fresnel's share of a path scales both
// channels alike and cancels, and light reflected off the glass goes into
// the black part.
#pragma once
#include "harness.h"

#include "core/display.h"
#include "core/image.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <glm/glm.hpp>
#include <string>
#include <vector>

namespace rgtest::optics {

constexpr double kPi = 3.14159265358979323846;

// The linear values of the 256 codes, as loadSky decodes them.
inline std::vector<double> rampValues() {
    std::vector<double> v;
    for (int k = 0; k < 256; ++k) v.push_back(float(rg::srgbToLinear(k / 255.0)));
    return v;
}

// Where along the ramp (0 ... 255, fractional) a pixel's red / green lies; -1 outside.
inline double rampPosition(const float* pixel) {
    static const std::vector<double> ramp = rampValues();
    if (!(pixel[1] > 0.05)) return -1;  // the black part of the sky (or the glass hid it)
    double q = double(pixel[0]) / pixel[1];
    for (int k = 0; k < 255; ++k)
        if (q >= ramp[k] && q <= ramp[k + 1]) return k + (q - ramp[k]) / (ramp[k + 1] - ramp[k]);
    return -1;
}

// A sky of width x height texels: code(column, row) gives red's code, or -1 for black.
template <typename F>
void writeRampSky(const std::string& path, uint32_t width, uint32_t height, F code) {
    rg::FloatImage sky{width, height, std::vector<float>(size_t(width) * height * 4, 1.0f)};
    for (uint32_t y = 0; y < height; ++y)
        for (uint32_t x = 0; x < width; ++x) {
            int k = code(int(x), int(y));
            float* p = &sky.rgba[4 * (size_t(y) * width + x)];
            p[0] = k < 0 ? 0.0f : float(rg::srgbToLinear(k / 255.0));
            p[1] = k < 0 ? 0.0f : 1.0f;
            p[2] = 0.0f;
        }
    rg::writePng(path, sky);
}

inline rg::FloatImage renderOptics(const std::string& exe, const std::string& scene, uint32_t width, uint32_t height,
                                   const std::string& pfm, std::vector<std::string> extra) {
    std::vector<std::string> args = {"--headless", "--validation", "--scene", scene, "--width", std::to_string(width),
                                     "--height", std::to_string(height), "--frames", "1", "--output", pfm};
    args.insert(args.end(), extra.begin(), extra.end());
    rgtest::RunResult r = rgtest::run(exe, args);
    EXPECT_EQ(r.exitCode, 0) << r.output;
    return rg::readPfm(pfm);
}

// [region lens_from_image]
// Looking back through the lens from a point on its axis, d behind the rear
// vertex: a ray leaving the eye at slope s leaves the lens at slope
// m(d) s, where m(d) = D - d / f (the thick lens's ray-transfer matrix, D =
// 1 - (n - 1) t / (n R)). The view through the lens is magnified by m: the
// sky's band climbs m times as fast across the lens as without it. m falls
// linearly with d, by 1/f (f: the effective focal length), and reaches 0,
// a view of one sky direction, at d = D f: the back focal length. At depth
// 2 a pixel sees only light that crossed each surface once; deeper, the
// 0.2 % that reflects twice inside the lens arrives from other directions
// of the band and blends in (a ghost image: m reads 1.3-6 % low at depth 6).
struct LensReading {
    std::vector<double> ds = {10, 20, 30}, ms;  // eye distances (mm) and magnifications
    double efl = 0, bfl = 0, slope = 0, intercept = 0;
};

// Chapter 12's lens (tools/make_meshes.cpp) of `material`, its axis along z.
inline LensReading lensFromImage(const std::string& exe, const std::string& dir, const std::string& meshDir,
                                 const nlohmann::json& material, std::vector<std::string> extra) {
    const uint32_t skyH = 2048, first = skyH / 2 - 128;  // the band: rows 896-1151, 11.25 degrees either side
    writeRampSky(dir + "/sky.png", 16, skyH, [&](int x, int y) {
        bool ahead = x >= 4 && x < 12;  // toward -z, where the camera looks
        return ahead ? std::clamp(y - int(first), 0, 255) : -1;
    });
    extra.insert(extra.end(), {"--depth", "2"});
    const uint32_t height = 201;
    LensReading lens;
    for (double d : lens.ds) {
        // Rays meet the lens within 0.8 mm of its axis: paraxial.
        double tanHalf = 0.8 / (d + 2.5), fov = 2 * std::atan(tanHalf) * 180 / kPi;
        nlohmann::json scene = {
            {"camera", {{"position", {0, 0, 2.5 + d}}, {"look_at", {0, 0, 0}}, {"fov_y_deg", fov}}},
            {"sky", {{"image", "sky.png"}}}, {"ambient", 0},
            {"materials", {{"lens", material}}},
            {"objects", {{{"type", "mesh"}, {"file", meshDir + "/lens.obj"}, {"material", "lens"},
                          {"transform", {{"rotate_deg", {90, 0, 0}}}}}}}};
        std::string name = dir + "/lens_" + std::to_string(int(d));
        std::ofstream(name + "_scene.json") << scene.dump();
        rg::FloatImage image = renderOptics(exe, name + "_scene.json", 3, height, name + ".pfm", extra);
        if (image.height != height) {
            ADD_FAILURE() << "no image at d " << d;
            return lens;
        }
        // Each row's slope in (tan of its elevation) against the slope it left with.
        double sx = 0, sy = 0, sxx = 0, sxy = 0, n = 0;
        for (uint32_t row = 0; row < height; ++row) {
            double p = rampPosition(&image.rgba[4 * (size_t(row) * 3 + 1)]);
            EXPECT_GT(p, 0) << "d " << d << " row " << row;
            double v = (first + p + 0.5) / skyH, elevation = kPi / 2 - v * kPi;
            double in = (1 - (row + 0.5) / height * 2) * tanHalf, out = std::tan(elevation);
            sx += in, sy += out, sxx += in * in, sxy += in * out, ++n;
        }
        lens.ms.push_back((n * sxy - sx * sy) / (n * sxx - sx * sx));
    }
    // m against d: a straight line, slope -1/f, zero at the back focal length.
    double sx = 0, sy = 0, sxx = 0, sxy = 0, n = double(lens.ds.size());
    for (size_t i = 0; i < lens.ds.size(); ++i)
        sx += lens.ds[i], sy += lens.ms[i], sxx += lens.ds[i] * lens.ds[i], sxy += lens.ds[i] * lens.ms[i];
    lens.slope = (n * sxy - sx * sy) / (n * sxx - sx * sx), lens.intercept = (sy - lens.slope * sx) / n;
    lens.efl = -1 / lens.slope, lens.bfl = -lens.intercept / lens.slope;
    return lens;
}
// [end]

// [region prism_from_image]
// A thin fan of horizontal rays through chapter 12's 60-degree prism near
// minimum deviation: each pixel's deviation is the direction it left in
// (read from the sky) minus the one it came in; the smallest over the fan
// is the minimum deviation.
struct PrismReading {
    double minimum = 0;          // degrees, between pixels (a parabola through the smallest three)
    int column = -1, seen = 0;   // where the smallest lies; pixels that saw the band
    std::vector<double> deviation;
};

inline PrismReading prismFromImage(const std::string& exe, const std::string& dir, const std::string& meshDir,
                                   const nlohmann::json& material, std::vector<std::string> extra) {
    // The band: 256 columns from 95 degrees of longitude (u = 0.5 + lon / 360), 0.117 degrees each.
    const uint32_t skyW = 3072;
    const int first = int(std::lround((0.5 + 95.0 / 360) * skyW));
    writeRampSky(dir + "/sky.png", skyW, 4, [&](int x, int) { return x >= first && x < first + 256 ? x - first : -1; });
    // make_meshes' prism: apex at z = -r, faces AB and AC either side of it. At
    // minimum deviation a ray crosses parallel to the base: it meets face AB
    // at 49.32 degrees, coming in along (sin 70.68, 0, -cos 70.68).
    const double r = 30 / std::sqrt(3.0), lonIn = 70.6776 * kPi / 180;
    glm::dvec3 mid(-r * std::sqrt(3.0) / 4, 15, -r / 4);  // the middle of face AB: A (0, -r), B (-r sqrt(3) / 2, r / 2)
    glm::dvec3 d(std::sin(lonIn), 0, -std::cos(lonIn)), eye = mid - 100.0 * d;
    const uint32_t width = 161, height = 21;  // the middle row's rays are horizontal
    double tanHalfX = std::tan(4 * kPi / 180), tanHalfY = tanHalfX * height / width;
    nlohmann::json scene = {
        {"camera", {{"position", {eye.x, eye.y, eye.z}}, {"look_at", {mid.x, mid.y, mid.z}},
                    {"fov_y_deg", 2 * std::atan(tanHalfY) * 180 / kPi}}},
        {"sky", {{"image", "sky.png"}}}, {"ambient", 0},
        {"materials", {{"prism", material}}},
        {"objects", {{{"type", "mesh"}, {"file", meshDir + "/prism.obj"}, {"material", "prism"}}}}};
    std::ofstream(dir + "/prism_scene.json") << scene.dump();
    // At depth 6: the light reflected inside leaves through the base, into the black.
    extra.insert(extra.end(), {"--depth", "6"});
    rg::FloatImage image = renderOptics(exe, dir + "/prism_scene.json", width, height, dir + "/prism.pfm", extra);
    PrismReading prism;
    if (image.width != width) {
        ADD_FAILURE() << "no image";
        return prism;
    }
    double best = 1e9;
    prism.deviation.assign(width, 1e9);
    for (uint32_t x = 0; x < width; ++x) {
        double p = rampPosition(&image.rgba[4 * (size_t(height / 2) * width + x)]);  // the middle row
        if (p < 0) continue;
        ++prism.seen;
        double lonOut = ((first + p + 0.5) / skyW - 0.5) * 2 * kPi;
        double sx = ((x + 0.5) / width * 2 - 1) * tanHalfX;  // the pixel's ray, turned from d by atan(sx)
        prism.deviation[x] = (lonOut - (lonIn + std::atan(sx))) * 180 / kPi;
        if (prism.deviation[x] < best) best = prism.deviation[x], prism.column = int(x);
    }
    EXPECT_GT(prism.seen, int(width) * 9 / 10) << "the fan should pass the prism into the band";
    if (prism.column <= 0 || prism.column >= int(width) - 1) {
        ADD_FAILURE() << "the minimum should lie inside the fan (column " << prism.column << ")";
        return prism;
    }
    // A parabola through the smallest and its neighbours finds the minimum between pixels.
    const std::vector<double>& dev = prism.deviation;
    double a = dev[prism.column - 1], b = dev[prism.column], c = dev[prism.column + 1];
    prism.minimum = b - (a - c) * (a - c) / (8 * (a - 2 * b + c));
    EXPECT_GT(dev[0], prism.minimum + 0.05);  // and more at both ends of the fan
    EXPECT_GT(dev[width - 1], prism.minimum + 0.05);
    return prism;
}
// [end]

}  // namespace rgtest::optics
