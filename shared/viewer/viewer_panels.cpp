// The viewer's overlay panels (chapter 04): the numbers, the chapter's
// parameters, the view and light section and the picked material (Dear ImGui).
#include "viewer/viewer.h"

#include <imgui.h>

#include <algorithm>
#include <cstdio>
#include <cstring>

namespace rg {

void Viewer::drawOverlay(uint32_t frame) {
    overlay_->beginFrame();
    ImGui::SetNextWindowPos(ImVec2(8, 8), ImGuiCond_FirstUseEver);
    ImGui::SetNextWindowBgAlpha(0.8f);
    ImGui::Begin(app_.window->initialTitle().c_str(), nullptr,
                 ImGuiWindowFlags_AlwaysAutoResize);
    // Compact, so that the picture stays in view: two lines of numbers, the
    // chapter's parameters, the material only once one is picked.
    const FrameTimes& times = loop_.times();
    double frameMs = times.cpuMs.empty() ? 0.0 : recentMedian(times.cpuMs);
    ImGui::Text("GPU %.2f ms  %.1f fps  %.1f Mrays/s",
                times.gpuMs.empty() ? 0.0 : recentMedian(times.gpuMs),
                frameMs > 0 ? 1000 / frameMs : 0.0, mraysPerS_);
    if (scale_ > 1)
        ImGui::Text("%ux%u at 1/%u while moving", rt_.width, rt_.height, scale_);
    else if (averaging)
        ImGui::Text("%ux%u, %llu rays, %u frames averaged", rt_.width, rt_.height,
                    (unsigned long long)raysPerFrame_, frame - firstFrame_ + 1);
    else
        ImGui::Text("%ux%u, %llu rays, one frame", rt_.width, rt_.height,
                    (unsigned long long)raysPerFrame_);
    if (chapterLine)  // the chapter's own: chapter 14's photons
        ImGui::Text("%s",
                    chapterLine(times.gpuMs.empty() ? 0.0 : recentMedian(times.gpuMs))
                        .c_str());
    ImGui::PushItemWidth(140);
    bool chapterParams = std::any_of(params_.all().begin(), params_.all().end(),
                                     [](const Param& p) { return p.section.empty(); });
    if (chapterParams &&
        ImGui::CollapsingHeader("Parameters", ImGuiTreeNodeFlags_DefaultOpen))
        parameterControls("");
    if (ImGui::CollapsingHeader("View and light")) viewControls();
    // a click just picked one
    if (std::exchange(openMaterial_, false)) ImGui::SetNextItemOpen(true);
    if (ImGui::CollapsingHeader("Material")) materialControls();
    ImGui::PopItemWidth();
    // every key, in one line
    ImGui::TextDisabled("keys: WASDQE R C H F2 F5 Esc (hover)");
    if (ImGui::IsItemHovered())
        ImGui::SetTooltip(
            "left drag orbits, right drag pans, wheel zooms, click picks\n"
            "W/A/S/D/Q/E fly (Shift: 4x), R resets the view, C prints the camera\n"
            "H hides this, F2 saves a screenshot, F5 reloads the shaders, Esc quits");
    std::string status = reload_ ? reload_->status() : std::string();
    // its file and line on a line
    if (const char* error = "shader error: "; status.rfind(error, 0) == 0) {
        size_t at = status.find(": ", std::strlen(error));
        status = "shader error in\n" +
                 status.substr(std::strlen(error), at - std::strlen(error)) + ":\n" +
                 (at == std::string::npos ? "" : status.substr(at + 2));
    }
    if (!status.empty()) {
        ImGui::PushTextWrapPos(ImGui::GetCursorPosX() + 280);
        if (reload_->failed())  // linear: the sRGB swapchain shows (255, 97, 89)
            ImGui::TextColored(ImVec4(1.0f, 0.12f, 0.1f, 1.0f), "%s", status.c_str());
        else ImGui::TextDisabled("%s", status.c_str());
        ImGui::PopTextWrapPos();
    }
    ImVec2 at = ImGui::GetWindowPos(), size = ImGui::GetWindowSize();
    overlayBox_[0] = at.x, overlayBox_[1] = at.y, overlayBox_[2] = size.x,
    overlayBox_[3] = size.y;
    ImGui::End();
}

// One control per declared parameter of a section (params.h): the command
// line's names, ranges and choices, so the two always agree.
void Viewer::parameterControls(const std::string& section) {
    for (const Param& p : params_.all()) {
        if (p.section != section) continue;
        ImGui::BeginDisabled(!p.live);
        const char* label = p.label.c_str();
        bool edited = false;
        switch (p.kind) {
        case Param::Kind::Integer:
            edited = ImGui::SliderInt(
                label, p.integer, int(p.min), int(p.max), "%d",
                ImGuiSliderFlags_AlwaysClamp |
                    (p.max - p.min > 64 ? ImGuiSliderFlags_Logarithmic : 0));
            break;
        case Param::Kind::Number:
            // from 0 it reaches down to 10^-(digits after the point): 06's epsilon, 1e-9
            if (p.logarithmic)
                edited = ImGui::SliderFloat(
                    label, p.number, float(p.min), float(p.max),
                    p.min == 0 ? "%.10f" : "%.3g",
                    ImGuiSliderFlags_AlwaysClamp | ImGuiSliderFlags_Logarithmic);
            else
                edited = ImGui::SliderFloat(label, p.number, float(p.min), float(p.max),
                                            "%.1f", ImGuiSliderFlags_AlwaysClamp);
            break;
        case Param::Kind::Choice: {
            std::vector<const char*> names;
            for (const std::string& c : p.choices) names.push_back(c.c_str());
            edited = ImGui::Combo(label, p.integer, names.data(), int(names.size()));
            break;
        }
        case Param::Kind::Toggle:
            edited = ImGui::Checkbox(label, p.toggle);
            break;
        case Param::Kind::Text:  // a file written at the end: shown, not edited
            ImGui::Text("%s: %s", label, p.text->empty() ? "-" : p.text->c_str());
            break;
        }
        ImGui::EndDisabled();
        if (ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled))
            ImGui::SetTooltip("%s %s%s", p.flag.c_str(), p.help.c_str(),
                              p.live ? "" : " (read at start only)");
        changed_ = changed_ || edited;
    }
}

// The camera's field of view, the exposure (a parameter: --exposure) and
// each point light's position (in the scene file's coordinates) and intensity.
void Viewer::viewControls() {
    float fov = float(camera_.camera().fovYDeg);
    if (ImGui::SliderFloat("fov", &fov, 5, 120, "%.1f deg",
                           ImGuiSliderFlags_AlwaysClamp)) {
        camera_.setFovY(fov);
        cameraDirty_ = true;
    }
    if (ImGui::IsItemHovered())
        ImGui::SetTooltip(
            "vertical field of view (the scene's camera fov_y_deg; R resets)");
    parameterControls("view");
    // Lights from chapter 05 on, the chapters that shade: they declare
    // --exposure. Chapter 04 shows normals, which no light changes.
    bool shading = std::any_of(params_.all().begin(), params_.all().end(),
                               [](const Param& p) { return p.flag == "--exposure"; });
    if (!shading) return;
    const Camera& c = camera_.camera();
    float speed = float(0.005 * glm::length(c.lookAt - c.position));  // per pixel dragged
    for (size_t i = 0; i < scene_.lights.size(); ++i) {
        PointLight& light = scene_.lights[i];
        ImGui::PushID(int(i));
        std::string label = "light " + std::to_string(i + 1);
        if (light.kind == PointLight::Kind::Directional) {  // chapter 14's sun
            glm::vec3 d = glm::vec3(light.direction);
            if (ImGui::DragFloat3(label.c_str(), &d.x, 0.01f, -1, 1, "%.2f") &&
                glm::length(d) > 0) {
                light.direction = glm::normalize(glm::dvec3(d));
                lightsDirty_ = true;
            }
            float e[3] = {float(light.irradiance.r), float(light.irradiance.g),
                          float(light.irradiance.b)};
            if (ImGui::ColorEdit3("irradiance", e,
                                  ImGuiColorEditFlags_Float | ImGuiColorEditFlags_HDR)) {
                light.irradiance = glm::max(glm::dvec3(e[0], e[1], e[2]), glm::dvec3(0));
                lightsDirty_ = true;
            }
            ImGui::PopID();
            continue;
        }
        glm::vec3 at = glm::vec3(light.position - scene_.origin);  // file = p - origin
        if (ImGui::DragFloat3(label.c_str(), &at.x, speed, 0, 0, "%.2f")) {
            light.position = glm::dvec3(at) + scene_.origin;
            // Typed past 1e7 from the eye, with shaders built without the
            // care for such lengths (needsCarefulNumerics's 1e8): held there.
            if (fastSizes_) light.position = glm::clamp(light.position, -1e7, 1e7);
            lightsDirty_ = true;
        }
        // chapter 14's point lights: radiant intensity, W/sr (power / 4 pi)
        float v[3] = {float(light.intensity.r), float(light.intensity.g),
                      float(light.intensity.b)};
        const char* unit = light.kind == PointLight::Kind::Point ? "W/sr" : "intensity";
        const ImGuiColorEditFlags flags =
            ImGuiColorEditFlags_Float | ImGuiColorEditFlags_HDR;
        if (ImGui::ColorEdit3(unit, v, flags)) {
            light.intensity = glm::max(glm::dvec3(v[0], v[1], v[2]), glm::dvec3(0));
            lightsDirty_ = true;
        }
        ImGui::PopID();
    }
}

void Viewer::materialControls() {
    std::vector<const char*> names;
    for (const Material& m : scene_.materials) names.push_back(m.name.c_str());
    ImGui::Combo("material", &selectedMaterial_, names.data(), int(names.size()));
    if (selectedMaterial_ < 0) {
        ImGui::TextDisabled("click an object to pick its material");
        return;
    }
    Material& m = scene_.materials[size_t(selectedMaterial_)];
    bool edited = false;
    auto color = [&](const char* label, glm::dvec3& value) {
        float v[3] = {float(value.x), float(value.y), float(value.z)};
        if (ImGui::ColorEdit3(label, v, ImGuiColorEditFlags_Float)) {
            value = glm::dvec3(v[0], v[1], v[2]);
            edited = true;
        }
    };
    auto number = [&](const char* label, double& value, float min, float max,
                      ImGuiSliderFlags flags = 0) {
        float v = float(value);
        if (ImGui::SliderFloat(label, &v, min, max, "%.3f",
                               flags | ImGuiSliderFlags_AlwaysClamp)) {
            value = v;
            edited = true;
        }
    };
    color("ka", m.ka);
    color("kd", m.kd);
    color("ks", m.ks);
    number("shininess", m.shininess, 1, 4096, ImGuiSliderFlags_Logarithmic);
    number("reflectivity", m.reflectivity, 0, 1);
    number("transmission", m.transmission, 0, 1);
    number("ior", m.ior, 1, 3);
    number("f0", m.f0, 0, 1);
    number("roughness", m.roughness, 0, 1);
    materialDirty_ = materialDirty_ || edited;
}

}  // namespace rg
