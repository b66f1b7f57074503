// Writes the procedural sky that the scenes use: an equirectangular image
// (longitude across, latitude down) with landmarks that tell up from down
// and left from right, so an inverted image (chapter 10) is unmistakable.
//   make_sky OUT.png [width]
// Directions: u = 0.5 + atan2(x, -z) / 2pi (looking down -z is the centre),
// v = acos(y) / pi (v = 0 straight up).
#include "core/files.h"

#include <stb_image_write.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <stdexcept>
#include <string>
#include <vector>

namespace {
constexpr double kPi = 3.14159265358979323846;

struct Rgb { double r, g, b; };

Rgb mix(Rgb a, Rgb b, double t) { return {a.r + (b.r - a.r) * t, a.g + (b.g - a.g) * t, a.b + (b.b - a.b) * t}; }

// A disc of angular radius `size` around (azimuth, elevation), soft edged.
double disc(double az, double el, double cAz, double cEl, double size) {
    double x = std::cos(el) * std::sin(az), y = std::sin(el), z = -std::cos(el) * std::cos(az);
    double cx = std::cos(cEl) * std::sin(cAz), cy = std::sin(cEl), cz = -std::cos(cEl) * std::cos(cAz);
    double angle = std::acos(std::clamp(x * cx + y * cy + z * cz, -1.0, 1.0));
    return std::clamp((size - angle) / 0.02 + 0.5, 0.0, 1.0);
}

double srgb(double linear) {
    double c = std::clamp(linear, 0.0, 1.0);
    return c <= 0.0031308 ? 12.92 * c : 1.055 * std::pow(c, 1 / 2.4) - 0.055;
}
}  // namespace

int main(int argc, char** argv) {
    if (argc < 2) {
        std::fprintf(stderr, "usage: make_sky OUT.png [width]\n");
        return 2;
    }
    int w = argc > 2 ? std::atoi(argv[2]) : 1024, h = w / 2;
    if (w < 16) return 2;
    std::vector<unsigned char> pixels(size_t(w) * h * 3);
    const double deg = kPi / 180;
    for (int j = 0; j < h; ++j)
        for (int i = 0; i < w; ++i) {
            double az = ((i + 0.5) / w - 0.5) * 2 * kPi;  // 0: -z (ahead), +pi/2: +x (right)
            double el = kPi / 2 - (j + 0.5) / h * kPi;    // +pi/2: up
            Rgb c;
            if (el >= 0) {  // sky: pale at the horizon, deep blue above
                c = mix({0.75, 0.82, 0.90}, {0.10, 0.25, 0.65}, std::pow(std::sin(el), 0.6));
            } else {        // ground: olive near the horizon, dark brown below, with a faint grid
                c = mix({0.30, 0.32, 0.18}, {0.10, 0.07, 0.05}, std::pow(-std::sin(el), 0.5));
                double grid = std::fabs(std::sin(az * 18)) < 0.06 || std::fabs(std::sin(el * 18)) < 0.06 ? 1.0 : 0.0;
                c = mix(c, {0.45, 0.42, 0.30}, 0.5 * grid);
            }
            // Landmarks: sun (yellow) high ahead, lake (green) low ahead,
            // red to the right, blue to the left.
            c = mix(c, {1.00, 0.85, 0.20}, disc(az, el, 0, 45 * deg, 10 * deg));
            c = mix(c, {0.05, 0.60, 0.20}, disc(az, el, 0, -35 * deg, 12 * deg));
            c = mix(c, {0.85, 0.08, 0.06}, disc(az, el, 35 * deg, 10 * deg, 9 * deg));
            c = mix(c, {0.08, 0.15, 0.85}, disc(az, el, -35 * deg, 10 * deg, 9 * deg));
            unsigned char* p = &pixels[3 * (size_t(j) * w + i)];
            p[0] = (unsigned char)std::lround(srgb(c.r) * 255);
            p[1] = (unsigned char)std::lround(srgb(c.g) * 255);
            p[2] = (unsigned char)std::lround(srgb(c.b) * 255);
        }
    std::string png;  // encoded in memory, then written whole (shared/core/files.h)
    auto append = [](void* context, void* data, int size) {
        static_cast<std::string*>(context)->append(static_cast<const char*>(data), size_t(size));
    };
    try {
        if (!stbi_write_png_to_func(append, &png, w, h, 3, pixels.data(), w * 3)) throw std::runtime_error("cannot encode");
        rg::writeFileAtomically(argv[1], png.data(), png.size());
    } catch (const std::exception& e) {
        std::fprintf(stderr, "make_sky: %s\n", e.what());
        return 1;
    }
    return 0;
}
