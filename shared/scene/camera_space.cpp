#include "scene/scene.h"

namespace rg {

// [region camera_space]
Scene toCameraSpace(Scene s) {
    glm::dvec3 eye = s.camera.position;  // every subtraction below is in double
    for (Object& o : s.objects) {
        o.transform[3] -= glm::dvec4(eye, 0);
        o.center -= eye;
    }
    for (PointLight& l : s.lights) l.position -= eye;
    s.camera.lookAt -= eye;
    s.camera.position = glm::dvec3(0);
    s.origin -= eye;
    return s;
}
// [end]

nlohmann::json cameraToJson(const Camera& camera, const glm::dvec3& origin) {
    auto array = [](const glm::dvec3& v) {
        return nlohmann::json::array({v.x, v.y, v.z});
    };
    return {{"position", array(camera.position - origin)},
            {"look_at", array(camera.lookAt - origin)},
            {"up", array(camera.up)},
            {"fov_y_deg", camera.fovYDeg}};
}

}  // namespace rg
