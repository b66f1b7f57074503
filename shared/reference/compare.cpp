// The reference's comparison (chapter 04 on): the error of an image
// against the reference, and its heat map.
#include "core/display.h"
#include "reference/reference.h"

#include <algorithm>
#include <cmath>

namespace rg {

ImageError compareImages(const FloatImage& test, const FloatImage& reference,
                         FloatImage* heatMap) {
    ImageError e;
    size_t n = size_t(test.width) * test.height;
    if (heatMap) *heatMap = {test.width, test.height, std::vector<float>(n * 4, 1.0f)};
    double sumSq = 0, sumSqDisplay = 0;
    uint64_t over = 0;
    for (size_t i = 0; i < n; ++i) {
        double worstDisplay = 0;
        bool finite = true;
        for (int c = 0; c < 3; ++c) {
            double a = test.rgba[4 * i + c], b = reference.rgba[4 * i + c];
            if (!std::isfinite(a)) {
                finite = false;
                continue;
            }
            double diff = a - b;
            sumSq += diff * diff;
            e.maxAbs = std::max(e.maxAbs, std::abs(diff));
            double dd = linearToSrgb(a) - linearToSrgb(b);
            sumSqDisplay += dd * dd;
            worstDisplay = std::max(worstDisplay, std::abs(dd));
        }
        if (!finite) {
            e.nonFinite++;
            worstDisplay = 1;
        }
        if (worstDisplay > 1.0 / 255.0 + 1e-12) over++;
        if (heatMap) {  // black -> red -> yellow -> white over 0 .. 8/255
            double h = std::min(1.0, worstDisplay * 255.0 / 8.0) * 3;
            float* p = &heatMap->rgba[4 * i];
            p[0] = float(std::clamp(h, 0.0, 1.0));
            p[1] = float(std::clamp(h - 1, 0.0, 1.0));
            p[2] = float(std::clamp(h - 2, 0.0, 1.0));
        }
    }
    e.rmse = std::sqrt(sumSq / double(3 * n));
    e.fracOver1_255 = double(over) / double(n);
    double mseDisplay = sumSqDisplay / double(3 * n);
    e.psnrDb = mseDisplay > 0 ? 10 * std::log10(1.0 / mseDisplay) : 999.0;
    return e;
}

}  // namespace rg
