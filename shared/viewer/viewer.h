// The window's interaction for the ray tracing chapters (04-11), in one
// place: the camera (orbit, pan, zoom, fly), the overlay with timings, the
// chapter's parameters and the picked object's material, the keys, and a
// target that follows the window's size. Headless runs get none of it.
//
//   mouse: left drag orbits, right or middle drag pans, wheel zooms, left click picks
//   keys:  W/A/S/D fly, Q/E down/up (Shift: faster), R reset, C print camera,
//          H overlay, F2 screenshot + report, F5 reload shaders, Esc or Ctrl+Q quit
#pragma once
#include "app/app.h"
#include "core/params.h"
#include "raytracing/rt_scene.h"
#include "reference/reference.h"
#include "viewer/camera_control.h"
#include "viewer/overlay.h"
#include "viewer/shader_reload.h"
#include "vulkan/frame_loop.h"

#include <chrono>
#include <functional>
#include <memory>
#include <optional>
#include <vector>

namespace rg {

// The median of the last (up to) 30 values: steady numbers in the overlay.
double recentMedian(const std::vector<double>& values);

class Viewer {
public:
    // Hooks into `loop` (overlay, resize). Changes it makes go to `scene`
    // (camera, materials), `opts` (size) and the values `params` point to,
    // so the end of the run (report, --reference) sees what is on screen.
    Viewer(App& app, Options& opts, Scene& scene, RtScene& rt, Image& target,
           FrameLoop& loop, Params params = {});
    ~Viewer();

    // Call first when recording a frame: applies the input, records the
    // uploads it needs (camera, material) into `cmd`, and returns how many
    // frames ago the picture last changed (0: this frame starts a new
    // progressive average). Headless: returns `frame`.
    uint32_t update(VkCommandBuffer cmd, uint32_t frame);

    // How many pixels to trace this frame: the target's size, or while a
    // view whose frames are slow moves, 1/s of its width and height (the
    // window shows that corner, scaled up). previewed(): the last frame was such.
    VkExtent2D launchSize() const;
    bool previewed() const { return scale_ > 1; }
    // This frame's change, if any, was of the view alone (the camera, the
    // preview's size, the window's): what does not depend on the camera
    // still holds (chapter 14's photon map). Headless: never.
    bool viewOnlyChanged() const { return viewOnly_; }

    // Set by the chapter each frame: its frames average while the picture
    // rests (--antialias, chapter 11's accumulation); the overlay counts them.
    bool averaging = false;
    // Set by the chapter: a line of its own numbers under the overlay's
    // first two, given the frames' GPU ms (chapter 14: photons/s, radius).
    std::function<std::string(double gpuMs)> chapterLine;

    // Shader hot reload (shader_reload.h), in a window: when a source of
    // `shaders` is saved, or on F5, and it compiles, `rebuild` makes the
    // pipeline again from the new stages, its objects in the queue it gets
    // (the previous reload's go when it returns). Headless: nothing.
    using Rebuild =
        std::function<void(const RtShaders& compiled, DeletionQueue& deletion)>;
    void reloadShaders(const RtShaders& shaders, Rebuild rebuild);

private:
    void handleInput(uint32_t frame);
    void handleKey(const Window::KeyPress& k, uint32_t frame, bool typing);
    void handlePointer(const Window::PointerEvent& e, bool overlayHasMouse);
    void handleFlying(double seconds);
    void drawOverlay(uint32_t frame);
    void parameterControls(const std::string& section);
    void viewControls();
    void materialControls();
    void resized();
    void screenshot(uint32_t frame);
    void measureRays();
    void pick(double x, double y);
    void applyReload();
    uint32_t previewScale(bool moving) const;

    App& app_;
    Options& opts_;
    Scene& scene_;
    // the shaders were built without the care for huge sizes (rt_scene.h):
    // a light edit keeps within the lengths that need none
    bool fastSizes_ = false;
    RtScene& rt_;
    Image& target_;
    FrameLoop& loop_;
    Params params_;
    CameraControl camera_;
    std::unique_ptr<Overlay> overlay_;
    bool overlayVisible_ = true;
    // the overlay's window as last drawn: x, y, width, height
    double overlayBox_[4] = {0, 0, 0, 0};
    DeletionQueue resizedTarget_;  // the target and ray counts of the last resize
    // one CPU ray per click, built at the first click
    std::optional<ReferenceRenderer> picker_;
    std::unique_ptr<ShaderReload> reload_;
    Rebuild rebuild_;
    std::unique_ptr<DeletionQueue> reloaded_;  // the pipeline of the last reload
    bool reloadFailed_ = false;
    // this frame traces 1/scale_ of the width and height
    uint32_t scale_ = 1;
    std::vector<uint8_t> frameScales_;   // each frame's scale_, by frame number
    // of the view, a light, a material or a parameter
    std::chrono::steady_clock::time_point lastChange_{};
    // F2 during a preview: taken at the next full frame
    bool pendingShot_ = false;
    bool previewNoted_ = false;
    std::vector<int> tapped_;  // keys pressed since the last frame

    uint32_t firstFrame_ = 0;  // of the current progressive average
    bool changed_ = false;     // view or parameter changed: restart the average
    bool viewOnly_ = false;    // this frame's change was the view's alone
    bool cameraDirty_ = true;  // upload the camera's matrices
    int selectedMaterial_ = -1;
    bool openMaterial_ = false;  // a pick opens the overlay's material section
    bool materialDirty_ = false;
    bool lightsDirty_ = false;
    // Mouse drags: where the button went down, whether ImGui had the mouse then.
    int dragButton_ = -1;
    double lastX_ = 0, lastY_ = 0, pressX_ = 0, pressY_ = 0;
    bool dragMoved_ = false;
    std::chrono::steady_clock::time_point lastUpdate_, lastTitle_, lastRays_;
    double mraysPerS_ = 0;
    uint64_t raysPerFrame_ = 0;
    int screenshots_ = 0;
};

}  // namespace rg
