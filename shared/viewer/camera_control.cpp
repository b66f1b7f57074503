#include "viewer/camera_control.h"

#include <algorithm>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>

namespace rg {

namespace {
constexpr double kRadiansPerPixel = 0.005;
constexpr double kMinPolarAngle = 0.01;  // radians from straight up or down

glm::dvec3 rotate(const glm::dvec3& v, const glm::dvec3& axis, double angle) {
    return glm::dvec3(glm::rotate(glm::dmat4(1.0), angle, axis) * glm::dvec4(v, 0));
}
}  // namespace

void CameraControl::orbit(double dx, double dy) {
    glm::dvec3 up = glm::normalize(camera_.up);
    glm::dvec3 offset = camera_.position - camera_.lookAt;  // look-at point -> eye
    offset = rotate(offset, up, -dx * kRadiansPerPixel);
    double length = glm::length(offset);
    if (length == 0) return;
    double polar = std::acos(std::clamp(glm::dot(offset / length, up), -1.0, 1.0));
    double turned =
        std::clamp(polar - dy * kRadiansPerPixel, kMinPolarAngle, M_PI - kMinPolarAngle);
    glm::dvec3 right = glm::cross(up, offset);
    if (glm::length(right) > 0)
        offset = rotate(offset, glm::normalize(right), polar - turned);
    camera_.position = camera_.lookAt + offset;
}

void CameraControl::pan(double dx, double dy, double viewportHeight) {
    glm::dvec3 forward = camera_.lookAt - camera_.position;
    double distance = glm::length(forward);
    glm::dvec3 right = glm::normalize(glm::cross(forward, camera_.up));
    glm::dvec3 up = glm::cross(right, forward / distance);
    // Scene units per pixel at the look-at point's distance.
    double perPixel = 2 * distance * std::tan(glm::radians(camera_.fovYDeg) / 2) /
                      std::max(1.0, viewportHeight);
    glm::dvec3 move = (-dx * right + dy * up) * perPixel;
    camera_.position += move;
    camera_.lookAt += move;
}

void CameraControl::zoom(double steps) {
    glm::dvec3 offset = camera_.position - camera_.lookAt;
    double length = glm::length(offset);
    double scaled =
        std::max(length * std::pow(0.85, steps), 1e-6 * std::max(1.0, length));
    camera_.position = camera_.lookAt + offset * (scaled / length);
}

void CameraControl::fly(const glm::dvec3& rightUpForward) {
    glm::dvec3 forward = glm::normalize(camera_.lookAt - camera_.position);
    glm::dvec3 right = glm::normalize(glm::cross(forward, camera_.up));
    glm::dvec3 move = rightUpForward.x * right +
                      rightUpForward.y * glm::normalize(camera_.up) +
                      rightUpForward.z * forward;
    camera_.position += move;
    camera_.lookAt += move;
}

glm::dvec3 CameraControl::rayDirection(double x, double y, double width,
                                       double height) const {
    glm::dvec3 forward = glm::normalize(camera_.lookAt - camera_.position);
    glm::dvec3 right = glm::normalize(glm::cross(forward, camera_.up));
    glm::dvec3 up = glm::cross(right, forward);
    double tanHalf = std::tan(glm::radians(camera_.fovYDeg) / 2);
    // y = -1: the top row
    double ndcX = (x + 0.5) / width * 2 - 1, ndcY = (y + 0.5) / height * 2 - 1;
    return glm::normalize(forward + ndcX * tanHalf * (width / height) * right -
                          ndcY * tanHalf * up);
}

}  // namespace rg
