// The unpolarized Fresnel equations, written out in double for the tests
// that check a chapter's optics against physics (chapters 09, 13, 14, 15),
// not against the CPU reference, which shares the GPU's rule.
#pragma once
#include <algorithm>
#include <cmath>

namespace rgtest {

// Reflectance from index n1 into n2 at cos(incidence) c; 1 past the
// critical angle (total internal reflection).
inline double fresnelEquations(double c, double n1, double n2) {
    double sinT = n1 / n2 * std::sqrt(std::max(0.0, 1 - c * c));
    if (sinT >= 1) return 1;
    double cosT = std::sqrt(1 - sinT * sinT);
    double rs = (n1 * c - n2 * cosT) / (n1 * c + n2 * cosT);
    double rp = (n2 * c - n1 * cosT) / (n2 * c + n1 * cosT);
    return 0.5 * (rs * rs + rp * rp);
}

}  // namespace rgtest
