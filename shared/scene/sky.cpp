#include "core/display.h"
#include "core/files.h"
#include "scene/scene.h"

#include <stb_image.h>

namespace rg {

SkyTexels loadSky(const Scene& scene) {
    SkyTexels sky;
    if (scene.sky.image.empty()) return sky;
    int w = 0, h = 0, n = 0;
    unsigned char* data = stbi_load(scene.sky.image.c_str(), &w, &h, &n, 4);
    if (!data) {
        std::string reason = stbi_failure_reason() ? stbi_failure_reason() : "";
        throw InputError(
            scene.path + ": sky.image: cannot read " + scene.sky.image + " (" +
            (reason.empty() ? "not an image stb_image reads, or a truncated one"
                            : reason) +
            ")");
    }
    sky.width = uint32_t(w);
    sky.height = uint32_t(h);
    sky.rgba.resize(size_t(w) * h * 4);
    for (size_t i = 0; i < size_t(w) * h; ++i) {
        for (int c = 0; c < 3; ++c)
            sky.rgba[4 * i + c] = float(srgbToLinear(data[4 * i + c] / 255.0));
        sky.rgba[4 * i + 3] = 1.0f;
    }
    stbi_image_free(data);
    return sky;
}

}  // namespace rg
