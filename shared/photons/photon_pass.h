// Chapter 14's photon pass as a chapter takes it (chapter/rt_chapter.h's
// hooks): its options, --caustics transmit's shaders, and the photon map
// (photon_map.h) traced before each frame's camera rays. Page 14 teaches
// it; chapters 14 and 15 use it.
#pragma once
#include "chapter/rt_chapter.h"

#include <functional>
#include <string>

namespace rg {

struct PhotonChapter {
    // --caustics, --photons, --radius, --alpha, ...
    std::function<void(Params&, RtChapterSettings&)> options;
    std::function<void(RtShaders&, const Scene&)> adaptShaders;
    std::function<FramePass(const FramePassContext&)> framePass;
};
// `photonShader`: the photons' ray generation shader ("14_caustics/photon.rgen").
PhotonChapter photonChapter(const std::string& photonShader);

}  // namespace rg
