// What a medium does to light (chapter 13): absorption and the index of
// refraction at a wavelength.
#include "scene/scene.h"

#include "host_device.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace rg {

glm::dvec3 absorptionOf(const glm::dvec3& color, double distance) {
    return -glm::log(color) / distance;  // exp(-sigma d) = color at d = distance
}

// [region sellmeier]
namespace {
double sellmeier(double nm, std::array<double, 8> c) {
    double l2 = nm * nm * 1e-6, n2 = 1;  // in square micrometres
    for (int i = 0; i < 4; ++i) n2 += c[i] * l2 / (l2 - c[4 + i]);
    return std::sqrt(n2);
}
}  // namespace

double glassIndex(Glass glass, double nm) {
    switch (glass) {
        case Glass::BK7: return sellmeier(nm, {SELLMEIER_BK7});
        case Glass::FusedSilica: return sellmeier(nm, {SELLMEIER_FUSED_SILICA});
        case Glass::Water: return sellmeier(nm, {SELLMEIER_WATER});
        case Glass::Diamond: return sellmeier(nm, {SELLMEIER_DIAMOND});
        case Glass::None: break;
    }
    return 1;
}

double indexAt(const Material& m, double nm) {
    if (m.glass != Glass::None) return glassIndex(m.glass, nm);
    if (m.dispersion <= 0) return m.ior;
    double abbe = 20 / m.dispersion;
    return std::max(m.ior + (m.ior - 1) / abbe * (523655 / (nm * nm) - 1.5168), 1.0);
}
// [end]

}  // namespace rg
