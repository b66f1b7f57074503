#include "viewer/viewer.h"

#include "app/report.h"
#include "app/rt_report.h"
#include "core/image.h"
#include "vk_check.h"

#include <imgui.h>

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <utility>

namespace rg {

namespace {
using Clock = std::chrono::steady_clock;

double secondsSince(Clock::time_point t) {
    return std::chrono::duration<double>(Clock::now() - t).count();
}

// [region viewer_uploads]
// Uploads recorded into the frame. Two frames are in flight, and both write
// the same camera buffer: before this frame's write, the previous frames'
// shaders must be done reading the old values (write after read: execution
// order is enough) and their own uploads must be done writing (write after
// write: a memory dependency, or the older write may land last). One buffer
// and a barrier rather than one buffer per frame in flight: the data travels
// inside the command buffer, so the CPU never races the GPU, and the
// shaders' descriptor sets stay one per chapter.
void beforeUpload(VkCommandBuffer cmd) {
    memoryBarrier(
        cmd,
        VK_PIPELINE_STAGE_RAY_TRACING_SHADER_BIT_KHR | VK_PIPELINE_STAGE_TRANSFER_BIT,
        VK_ACCESS_TRANSFER_WRITE_BIT,  // the last upload's writes
        VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT);
}
// read after write: this frame's shaders see the new values
void afterUpload(VkCommandBuffer cmd) {
    memoryBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT,
                  VK_PIPELINE_STAGE_RAY_TRACING_SHADER_BIT_KHR,
                  VK_ACCESS_UNIFORM_READ_BIT | VK_ACCESS_SHADER_READ_BIT);
}
// [end]
}  // namespace

// The median of the last (up to) 30 values: steady numbers in the overlay.
double recentMedian(const std::vector<double>& values) {
    size_t n = std::min<size_t>(values.size(), 30);
    return median(std::vector<double>(values.end() - n, values.end()));
}

Viewer::Viewer(App& app, Options& opts, Scene& scene, RtScene& rt, Image& target,
               FrameLoop& loop, Params params)
    : app_(app),
      opts_(opts),
      scene_(scene),
      rt_(rt),
      target_(target),
      loop_(loop),
      params_(std::move(params)),
      camera_(scene.camera) {
    if (!app.window) return;
    fastSizes_ = !carefulNumerics(opts, scene).sizes;
    overlay_ = std::make_unique<Overlay>(app.gpu, *app.window);
    overlayVisible_ = opts.ui;
    loop.overlay = [this](VkCommandBuffer cmd, uint32_t image) {
        if (overlayVisible_) overlay_->record(cmd, image);
    };
    loop.swapchainRecreated = [this] { resized(); };
    lastUpdate_ = lastTitle_ = lastRays_ = Clock::now();
    std::printf(
        "Window: left drag orbits, right drag pans, wheel zooms, click picks; "
        "W/A/S/D/Q/E fly, R resets, C prints the camera, H overlay, F2 screenshot, "
        "F5 reloads shaders, Esc quits\n");
}

Viewer::~Viewer() {
    if (!app_.window) return;
    vkDeviceWaitIdle(app_.gpu.device);  // before the resized target and the overlay go
    loop_.overlay = nullptr;
    loop_.swapchainRecreated = nullptr;
}

// [region viewer_update]
uint32_t Viewer::update(VkCommandBuffer cmd, uint32_t frame) {
    if (!app_.window) return frame;  // headless: one fixed view, one long average
    double seconds = std::min(0.1, secondsSince(lastUpdate_));
    lastUpdate_ = Clock::now();
    // the window shows a full frame
    if (pendingShot_ && frame > 0 && frameScales_[frame - 1] == 1) {
        pendingShot_ = false;
        screenshot(frame);
    }
    handleInput(frame);
    if (reload_) applyReload();  // F5 or a saved shader
    handleFlying(seconds);
    if (overlayVisible_) {
        if (secondsSince(lastRays_) > 1) measureRays();
        drawOverlay(frame);
    }

    bool upload = cameraDirty_ || materialDirty_ || lightsDirty_;
    // lights, materials, parameters and shaders change what light does
    bool lighting = materialDirty_ || lightsDirty_ || changed_;
    if (upload) beforeUpload(cmd);
    if (cameraDirty_) {  // the two matrices at the start of RtCamera (host_device.h)
        scene_.camera = camera_.camera();  // the report and --reference see this view
        glm::mat4 matrices[2];
        cameraMatrices(scene_.camera, double(rt_.width) / rt_.height, matrices[0],
                       matrices[1]);
        vkCmdUpdateBuffer(cmd, rt_.camera.handle, 0, sizeof matrices, matrices);
    }
    if (materialDirty_) {
        gpu::GpuMaterial m =
            toGpuMaterial(scene_.materials[size_t(selectedMaterial_)], scene_);
        vkCmdUpdateBuffer(cmd, rt_.materials.handle, sizeof m * size_t(selectedMaterial_),
                          sizeof m, &m);
    }
    if (lightsDirty_) {  // all of them: a few 32-byte records
        std::vector<gpu::GpuLight> lights = toGpuLights(scene_);
        vkCmdUpdateBuffer(cmd, rt_.lights.handle, 0, lights.size() * sizeof lights[0],
                          lights.data());
    }
    if (upload) afterUpload(cmd);
    // The first frame's upload is no change: a slow start shows no preview.
    if ((upload || changed_) && !frameScales_.empty()) lastChange_ = Clock::now();
    uint32_t scale = previewScale(secondsSince(lastChange_) < 0.25 &&
                                  // the last frame is full
                                  !glfwWindowShouldClose(app_.window->handle()));
    changed_ = changed_ || scale != scale_;  // a new size: a new average
    if (scale > 1 && !std::exchange(previewNoted_, true)) {
        std::printf("slow frames: 1/%u of the width and height while the view moves\n",
                    scale);
        std::fflush(stdout);
    }
    viewOnly_ = (cameraDirty_ || scale != scale_) && !lighting;
    scale_ = scale;
    frameScales_.push_back(uint8_t(scale));  // index: frame
    loop_.shown = launchSize();
    if (upload || changed_) firstFrame_ = frame;  // a new picture: restart the average
    cameraDirty_ = materialDirty_ = lightsDirty_ = changed_ = false;

    if (secondsSince(lastTitle_) > 0.25 && !loop_.times().gpuMs.empty()) {
        char title[256];
        const FrameTimes& times = loop_.times();
        std::snprintf(title, sizeof title, "%s - GPU %.2f ms, frame %.2f ms",
                      app_.window->initialTitle().c_str(), recentMedian(times.gpuMs),
                      recentMedian(times.cpuMs));
        app_.window->setTitle(title);
        lastTitle_ = Clock::now();
    }
    return frame - firstFrame_;
}
// [end]

// Keys and the pointer in the order they came: after a slow frame (a second
// on lavapipe) a whole drag and the R after it are in one poll, and the R
// must come last.
void Viewer::handleInput(uint32_t frame) {
    bool typing = overlayVisible_ && overlay_->wantsKeyboard();  // into an overlay field
    bool overlayHasMouse = overlayVisible_ && overlay_->wantsMouse();
    double scroll = app_.window->takeScroll();
    if (scroll != 0 && !overlayHasMouse) {
        camera_.zoom(scroll);
        cameraDirty_ = true;
    }
    tapped_.clear();
    std::vector<Window::KeyPress> keys = app_.window->takeKeys();
    std::vector<Window::PointerEvent> pointer = app_.window->takePointer();
    size_t k = 0, p = 0;
    while (k < keys.size() || p < pointer.size()) {
        if (p == pointer.size() || (k < keys.size() && keys[k].order < pointer[p].order))
            handleKey(keys[k++], frame, typing);
        else handlePointer(pointer[p++], overlayHasMouse);
    }
}

void Viewer::handleKey(const Window::KeyPress& k, uint32_t frame, bool typing) {
    // pressed since the last frame, maybe let go again (handleFlying)
    tapped_.push_back(k.key);
    if (k.key == GLFW_KEY_ESCAPE || (k.key == GLFW_KEY_Q && (k.mods & GLFW_MOD_CONTROL)))
        glfwSetWindowShouldClose(app_.window->handle(), GLFW_TRUE);
    if (typing) return;
    if (k.key == GLFW_KEY_R) {
        camera_.reset();
        cameraDirty_ = true;
    } else if (k.key == GLFW_KEY_C) {  // a block to paste into the scene file
        std::printf("\"camera\": %s\n",
                    cameraToJson(camera_.camera(), scene_.origin).dump().c_str());
        std::fflush(stdout);
    } else if (k.key == GLFW_KEY_H) {
        overlayVisible_ = !overlayVisible_;
    } else if (k.key == GLFW_KEY_F2) {
        // a preview is on screen: the next full frame
        if (scale_ > 1) pendingShot_ = true;
        else screenshot(frame);
    } else if (k.key == GLFW_KEY_F5 && reload_) {
        reload_->request();
    }
}

// Presses, moves and releases as events, in order: after a slow frame a
// whole click or drag is in one poll. A press on the overlay is the
// overlay's. ImGui's own answer is the last frame's: a pointer that has just
// come onto the overlay and clicked is not yet its. So the overlay's box too.
void Viewer::handlePointer(const Window::PointerEvent& e, bool overlayHasMouse) {
    const double* b = overlayBox_;
    bool onOverlay = overlayHasMouse || (overlayVisible_ && e.x >= b[0] && e.y >= b[1] &&
                                         e.x < b[0] + b[2] && e.y < b[1] + b[3]);
    using Event = Window::PointerEvent;
    if (e.kind == Event::Press && dragButton_ < 0 && !onOverlay) {
        dragButton_ = e.button;
        pressX_ = lastX_ = e.x;
        pressY_ = lastY_ = e.y;
        dragMoved_ = false;
    } else if (e.kind == Event::Move && dragButton_ >= 0) {
        dragMoved_ = dragMoved_ || std::abs(e.x - pressX_) + std::abs(e.y - pressY_) > 3;
        if (dragMoved_) {
            if (dragButton_ == GLFW_MOUSE_BUTTON_LEFT)
                camera_.orbit(e.x - lastX_, e.y - lastY_);
            else camera_.pan(e.x - lastX_, e.y - lastY_, app_.window->extent.height);
            cameraDirty_ = true;
        }
        lastX_ = e.x;
        lastY_ = e.y;
    } else if (e.kind == Event::Release && e.button == dragButton_) {
        // a click, not a drag
        if (dragButton_ == GLFW_MOUSE_BUTTON_LEFT && !dragMoved_) pick(e.x, e.y);
        dragButton_ = -1;
    }
}

void Viewer::handleFlying(double seconds) {
    GLFWwindow* w = app_.window->handle();
    if ((overlayVisible_ && overlay_->wantsKeyboard()) ||
        glfwGetKey(w, GLFW_KEY_LEFT_CONTROL) == GLFW_PRESS)
        return;
    // Held now, or pressed and let go since the last frame: a short tap
    // still moves when a frame takes longer than the tap (lavapipe).
    auto held = [&](int key) {
        bool tapped = std::find(tapped_.begin(), tapped_.end(), key) != tapped_.end();
        return glfwGetKey(w, key) == GLFW_PRESS || tapped ? 1.0 : 0.0;
    };
    glm::dvec3 move{held(GLFW_KEY_D) - held(GLFW_KEY_A),
                    held(GLFW_KEY_E) - held(GLFW_KEY_Q),
                    held(GLFW_KEY_W) - held(GLFW_KEY_S)};
    if (move == glm::dvec3(0)) return;
    // Half the distance to the look-at point per second (it moves along, so
    // the speed stays): slow close up, fast in a wide view. Shift: 4x.
    const Camera& c = camera_.camera();
    double speed =
        0.5 * glm::length(c.lookAt - c.position) * (held(GLFW_KEY_LEFT_SHIFT) ? 4 : 1);
    camera_.fly(move * speed * seconds);
    cameraDirty_ = true;
}

void Viewer::pick(double x, double y) {
    if (!picker_) picker_.emplace(scene_);
    int w = 0, h = 0;
    glfwGetWindowSize(app_.window->handle(), &w, &h);
    // target pixels
    double px = x * rt_.width / std::max(1, w), py = y * rt_.height / std::max(1, h);
    glm::dvec3 direction = camera_.rayDirection(px, py, rt_.width, rt_.height);
    ReferenceHit hit =
        picker_->trace(camera_.camera().position, direction, picker_->eyeTmin(), 1e30);
    selectedMaterial_ = hit.t < 0 ? -1 : int(scene_.objects[hit.object].material);
    openMaterial_ = selectedMaterial_ >= 0;
}

// [region viewer_resize]
// The swapchain was re-created (the device is idle): the ray traced image
// follows the window's size, so the blit copies it 1:1.
void Viewer::resized() {
    overlay_->swapchainRecreated();
    VkExtent2D size = app_.window->extent;
    if (size.width == 0 || size.height == 0 ||
        (size.width == target_.extent.width && size.height == target_.extent.height))
        return;
    resizedTarget_.flush();  // the previous resize's target and ray counts
    resizeTarget(app_.gpu, resizedTarget_, rt_, target_, size);
    loop_.prepareTarget();
    opts_.width = int(size.width);  // the report and --reference use the new size
    opts_.height = int(size.height);
    cameraDirty_ = true;            // a new aspect ratio
    std::printf("resized: the target is now %ux%u\n", size.width, size.height);
    std::fflush(stdout);
}
// [end]

void Viewer::reloadShaders(const RtShaders& shaders, Rebuild rebuild) {
    if (!app_.window) return;
    reload_ = std::make_unique<ShaderReload>(
        shaders, opts_.shaderSource.empty() ? builtSourceRoot()
                                            : std::filesystem::path(opts_.shaderSource));
    rebuild_ = std::move(rebuild);
}

// [region viewer_reload]
// New stages compiled: the frames in flight still trace with the old
// pipeline, so it goes only after they are done, and only once the new one
// was made. The camera stays; the average starts again.
void Viewer::applyReload() {
    std::optional<RtShaders> compiled = reload_->poll();
    bool failed = reload_->failed();
    if (failed && !reloadFailed_) overlayVisible_ = true;  // where the error is shown
    reloadFailed_ = failed;
    if (!compiled) return;
    auto begin = Clock::now();
    VK_CHECK(vkDeviceWaitIdle(app_.gpu.device));
    auto next = std::make_unique<DeletionQueue>();
    try {
        rebuild_(*compiled, *next);
    } catch (const std::exception& e) {  // what it made so far goes with `next`
        reload_->rebuildFailed(e.what());
        return;
    }
    reloaded_ = std::move(next);  // destroys the pipeline before it
    reload_->rebuilt(secondsSince(begin));
    changed_ = true;
}
// [end]

// [region viewer_preview]
// Responsive while frames are slow (lavapipe: chapter 13 takes over a second
// at 800x450). While the view changes, trace 1/s of the width and height,
// with s such that a frame takes about kPreviewMs by the last measured one;
// once it rests for a quarter of a second, full frames again.
uint32_t Viewer::previewScale(bool moving) const {
    constexpr double kPreviewMs = 50;
    const std::vector<double>& gpuMs = loop_.times().gpuMs;  // gpuMs[k]: frame k's
    if (!moving || gpuMs.empty() || gpuMs.size() > frameScales_.size()) return 1;
    double s = frameScales_[gpuMs.size() - 1];
    double fullMs = gpuMs.back() * s * s;  // that frame at full size
    return uint32_t(std::clamp(std::ceil(std::sqrt(fullMs / kPreviewMs)), 1.0, 8.0));
}

VkExtent2D Viewer::launchSize() const {
    return {(rt_.width + scale_ - 1) / scale_, (rt_.height + scale_ - 1) / scale_};
}
// [end]

void Viewer::measureRays() {
    VK_CHECK(vkQueueWaitIdle(app_.gpu.queue));  // the counts of finished frames only
    raysPerFrame_ = countRays(app_.gpu, rt_);
    const std::vector<double>& gpuMs = loop_.times().gpuMs;
    mraysPerS_ = mraysPerSecond(raysPerFrame_, gpuMs.empty() ? 0 : recentMedian(gpuMs));
    lastRays_ = Clock::now();
}

// F2: the ray traced image as it is (never the overlay) and a report that
// says how to get it again: camera, size, parameters.
void Viewer::screenshot(uint32_t frame) {
    // the last finished frame is what the window shows
    VK_CHECK(vkQueueWaitIdle(app_.gpu.queue));
    FloatImage image =
        readImage(app_.gpu, target_, VK_PIPELINE_STAGE_RAY_TRACING_SHADER_BIT_KHR);
    std::string stem;
    do stem = opts_.chapter + "_shot" + std::to_string(++screenshots_);
    while (std::filesystem::exists(stem + ".png"));
    writePng(stem + ".png", image);
    nlohmann::json report = makeReport(opts_, app_.gpu, loop_.times());
    report["scene"] = scene_.path;
    report["camera"] = cameraToJson(camera_.camera(), scene_.origin);
    // the frames in the picture
    report["accumulated_frames"] = averaging ? frame - firstFrame_ : 1;
    if (selectedMaterial_ >= 0)
        report["selected_material"] = scene_.materials[size_t(selectedMaterial_)].name;
    report["parameters"] = params_.values();
    report["lights"] = nlohmann::json::array();  // as the View and light section has them
    for (const PointLight& l : scene_.lights) {
        glm::dvec3 p = l.position - scene_.origin;  // the scene file's coordinates
        auto array = [](const glm::dvec3& v) { return nlohmann::json{v.x, v.y, v.z}; };
        if (l.kind == PointLight::Kind::Directional)  // as the scene format writes them
            report["lights"].push_back({{"type", "directional"},
                                        {"direction", array(l.direction)},
                                        {"irradiance", array(l.irradiance)}});
        else if (l.kind == PointLight::Kind::Point)
            report["lights"].push_back(
                {{"position", array(p)}, {"power", array(l.intensity * (4 * M_PI))}});
        else
            report["lights"].push_back(
                {{"position", array(p)}, {"intensity", array(l.intensity)}});
    }
    writeReport(stem + ".json", report);
    std::printf("F2: wrote %s.png and %s.json\n", stem.c_str(), stem.c_str());
    std::fflush(stdout);
}

}  // namespace rg
