// The window's camera (chapters 04-11), as in most ray tracing samples:
// orbit around the look-at point, pan, zoom, and fly. It moves the camera
// in the scene's camera space (scene.h, toCameraSpace), in double.
#pragma once
#include "scene/scene.h"

namespace rg {

class CameraControl {
public:
    explicit CameraControl(const Camera& start) : start_(start), camera_(start) {}

    // Turns the eye around the look-at point: a drag of (dx, dy) pixels.
    // The elevation stops short of the poles, so `up` stays meaningful.
    void orbit(double dx, double dy);
    // Moves eye and look-at point together in the image plane, so that the
    // point looked at follows the mouse (viewport height in pixels).
    void pan(double dx, double dy, double viewportHeight);
    // Towards (steps > 0) or away from the look-at point, by 15 % a step.
    void zoom(double steps);
    // Moves eye and look-at point by (right, up, forward) in scene units.
    void fly(const glm::dvec3& rightUpForward);
    void reset() { camera_ = start_; }
    // the overlay's fov slider
    void setFovY(double degrees) { camera_.fovYDeg = degrees; }

    const Camera& camera() const { return camera_; }

    // The unit direction through a pixel centre, as shaders/common/camera.glsl
    // computes it (y = 0 is the top row): for picking an object with one ray.
    glm::dvec3 rayDirection(double x, double y, double width, double height) const;

private:
    Camera start_, camera_;
};

}  // namespace rg
