// The reference's geometry (chapters 03-04, 12): its own sphere, quad and
// watertight triangle tests in double, its BVH, the camera's rays and the
// sky (a mesh's textures: textures.cpp).
#include "reference/reference.h"

#include "core/display.h"

#include <algorithm>
#include <cstdint>
#include <cmath>

namespace rg {

namespace {
constexpr double kPi = 3.14159265358979323846;
// 64 units of double's relative rounding (2^-53): the reference's error
// bounds, the GPU's (hit_error.glsl) in double precision.
constexpr double kRounding = 64.0 / 9007199254740992.0;
double maxMagnitude(const glm::dvec3& v) {
    return std::max({std::abs(v.x), std::abs(v.y), std::abs(v.z)});
}
}

bool referenceUnitSphere(const glm::dvec3& o, const glm::dvec3& d, double& t0,
                         double& t1) {
    // |o + t d|^2 = 1: a t^2 + 2 h t + c = 0 with h = o.d. The discriminant is
    // taken as a (1 - |o - (o.d / a) d|^2) (no cancellation), and the smaller
    // root in magnitude as c / q (no subtraction of near-equal numbers).
    double a = glm::dot(d, d), h = glm::dot(o, d), c = glm::dot(o, o) - 1.0;
    glm::dvec3 perpendicular = o - (h / a) * d;
    double disc = a * (1.0 - glm::dot(perpendicular, perpendicular));
    if (disc < 0) return false;
    double q = -(h + std::copysign(std::sqrt(disc), h));
    if (q == 0) {
        t0 = t1 = 0;
        return c == 0;
    }
    t0 = c / q;
    t1 = q / a;
    if (t0 > t1) std::swap(t0, t1);
    return true;
}

namespace {
struct BoxItem {
    glm::dvec3 lo, hi, centre;
    uint32_t id;
};

// Recursive median split: nth_element on the longest axis of the centres.
void buildTree(std::vector<BoxItem>& items, ReferenceRenderer::Bvh& bvh) {
    if (items.empty()) return;
    auto build = [&](auto& self, size_t first, size_t last) -> uint32_t {
        uint32_t index = uint32_t(bvh.nodes.size());
        bvh.nodes.push_back({});
        glm::dvec3 lo(1e300), hi(-1e300), clo(1e300), chi(-1e300);
        for (size_t k = first; k < last; ++k) {
            lo = glm::min(lo, items[k].lo), hi = glm::max(hi, items[k].hi);
            clo = glm::min(clo, items[k].centre), chi = glm::max(chi, items[k].centre);
        }
        bvh.nodes[index].lo = lo;
        bvh.nodes[index].hi = hi;
        if (last - first <= 4) {
            bvh.nodes[index].first = uint32_t(bvh.items.size());
            bvh.nodes[index].count = uint32_t(last - first);
            for (size_t k = first; k < last; ++k) bvh.items.push_back(items[k].id);
            return index;
        }
        glm::dvec3 extent = chi - clo;
        int axis = extent.x >= extent.y && extent.x >= extent.z ? 0
                   : extent.y >= extent.z                       ? 1
                                                                : 2;
        size_t mid = (first + last) / 2;
        std::nth_element(items.begin() + long(first), items.begin() + long(mid),
                         items.begin() + long(last),
                         [axis](const BoxItem& a, const BoxItem& b) {
                             return a.centre[axis] < b.centre[axis];
                         });
        self(self, first, mid);  // the left child is index + 1
        uint32_t right = self(self, mid, last);
        bvh.nodes[index].right = right;
        return index;
    };
    build(build, 0, items.size());
}

// Visits the leaves' items whose boxes the ray meets within (tMin, closest()):
// `closest` is read at every node, so a hit found shortens the rest.
template <typename Closest, typename Visit>
void traverseTree(const ReferenceRenderer::Bvh& bvh, const glm::dvec3& origin,
                  const glm::dvec3& direction, double tMin, Closest closest,
                  Visit visit) {
    if (bvh.nodes.empty()) return;
    glm::dvec3 inv = 1.0 / direction;  // +-inf for an axis the ray is parallel to
    uint32_t stack[128];
    int top = 0;
    stack[top++] = 0;
    while (top > 0) {
        const ReferenceRenderer::BvhNode& node = bvh.nodes[stack[--top]];
        // Slab test against (tMin, the closest hit so far); NaN (0 * inf) leaves an axis
        // out.
        double t0 = tMin, t1 = closest();
        for (int a = 0; a < 3; ++a) {
            double n = (node.lo[a] - origin[a]) * inv[a],
                   f = (node.hi[a] - origin[a]) * inv[a];
            if (n > f) std::swap(n, f);
            if (n > t0) t0 = n;
            if (f < t1) t1 = f;
        }
        if (t0 > t1 * (1 + 1e-12) + 1e-300) continue;
        if (node.count > 0) {
            for (uint32_t k = node.first; k < node.first + node.count; ++k)
                visit(bvh.items[k]);
        } else {
            stack[top++] = node.right;
            // the left child first
            stack[top++] = uint32_t(&node - bvh.nodes.data()) + 1;
        }
    }
}

// Pads a box by its rounding, so that no part of what it holds is outside.
void padBox(BoxItem& item) {
    glm::dvec3 pad = 1e-9 * (item.hi - item.lo + glm::abs(item.lo) + glm::abs(item.hi));
    item.lo -= pad;
    item.hi += pad;
    item.centre = 0.5 * (item.lo + item.hi);
}
}  // namespace

ReferenceRenderer::ReferenceRenderer(const Scene& scene) : scene_(scene) {
    for (const auto& t : scene.textures) rayCones_ = rayCones_ || t->levels.size() > 1;
    // chapter 12: in double, each with its triangles' tree
    for (const auto& mesh : scene.meshes) {
        MeshData& m = meshes_.emplace_back();
        for (const glm::vec3& v : mesh->vertices)
            m.vertices.push_back(v), m.size = std::max(m.size, maxMagnitude(v));
        for (const glm::vec3& n : mesh->normals) m.normals.push_back(n);
        for (const glm::vec2& uv : mesh->texcoords) m.texcoords.push_back(uv);
        m.indices = mesh->indices;
        std::vector<BoxItem> items;
        for (uint32_t t = 0; t < m.indices.size() / 3; ++t) {
            BoxItem item{glm::dvec3(1e300), glm::dvec3(-1e300), {}, t};
            for (int c = 0; c < 3; ++c) {
                item.lo = glm::min(item.lo, m.vertices[m.indices[3 * t + c]]);
                item.hi = glm::max(item.hi, m.vertices[m.indices[3 * t + c]]);
            }
            padBox(item);
            items.push_back(item);
        }
        buildTree(items, m.bvh);
    }
    for (const auto& o : scene.objects) {
        worldToObject_.push_back(glm::inverse(o.transform));
        const glm::dmat4& m = o.transform;
        // of the object-space numbers
        double extent = o.type == ShapeType::Mesh ? meshes_[o.mesh].size : 1.0;
        objectSize_.push_back(maxMagnitude(glm::dvec3(m[3])) +
                              largestStretch(m) * extent);
    }
    buildBvh();
    SkyTexels sky = loadSky(scene);
    skyWidth_ = sky.width;
    skyHeight_ = sky.height;
    sky_.resize(size_t(sky.width) * sky.height * 3);
    for (size_t i = 0; i < size_t(sky.width) * sky.height; ++i)
        for (int c = 0; c < 3; ++c) sky_[3 * i + c] = sky.rgba[4 * i + c];
}

void ReferenceRenderer::hitObject(uint32_t i, const glm::dvec3& origin,
                                  const glm::dvec3& direction, double tMin, double tMax,
                                  ReferenceHit& best) const {
    const Object& obj = scene_.objects[i];
    if (obj.hidden) return;  // a copy of an earlier object (scene_file.cpp's rule)
    const glm::dmat4& inv = worldToObject_[i];
    glm::dvec3 o = glm::dvec3(inv * glm::dvec4(origin, 1.0));
    // t is the same in both spaces
    glm::dvec3 d = glm::dvec3(inv * glm::dvec4(direction, 0.0));
    double t = -1;
    glm::dvec3 localNormal, localShadingNormal(0);
    bool front = true;
    TriangleHit h;  // a mesh's
    if (obj.type == ShapeType::Sphere) {
        double t0, t1;
        if (!referenceUnitSphere(o, d, t0, t1)) return;
        if (t0 > tMin && t0 < tMax) t = t0;
        else if (t1 > tMin && t1 < tMax) { t = t1; front = false; }
        else return;
        localNormal = o + t * d;
    } else if (obj.type == ShapeType::Mesh) {
        const MeshData& mesh = meshes_[obj.mesh];
        const Material& material = scene_.materials[obj.material];
        // The texture coordinate at a point of a triangle.
        auto uvAt = [&](uint32_t triangle, const glm::dvec3& w) {
            const uint32_t* v = &mesh.indices[3 * triangle];
            return w.x * mesh.texcoords[v[0]] + w.y * mesh.texcoords[v[1]] +
                   w.z * mesh.texcoords[v[2]];
        };
        // Chapter 12's alpha test (alpha.rahit): a hit counts where the base
        // colour's alpha reaches the cutoff.
        HitFilter counts;
        if (material.alphaCutoff > 0)
            counts = [&](uint32_t triangle, const glm::dvec3& w) {
                double alpha = material.alpha;
                if (material.texture >= 0 && !mesh.texcoords.empty())
                    alpha *= sampleAlpha(*scene_.textures[material.texture],
                                         uvAt(triangle, w));
                return alpha >= material.alphaCutoff;
            };
        h = intersectMesh(mesh, o, d, tMin, tMax, counts);
        if (h.t < 0) return;
        t = h.t;
        front = h.front;
        const uint32_t* v = &mesh.indices[3 * h.triangle];
        localNormal = glm::cross(mesh.vertices[v[1]] - mesh.vertices[v[0]],
                                 mesh.vertices[v[2]] - mesh.vertices[v[0]]);
        if (!mesh.normals.empty())
            localShadingNormal = h.weights.x * mesh.normals[v[0]] +
                                 h.weights.y * mesh.normals[v[1]] +
                                 h.weights.z * mesh.normals[v[2]];
    } else {
        if (d.y == 0) return;  // parallel to the plane
        t = -o.y / d.y;
        if (!(t > tMin && t < tMax)) return;
        glm::dvec3 p = o + t * d;
        if (std::abs(p.x) > 1 || std::abs(p.z) > 1) return;
        localNormal = {0, 1, 0};
    }
    if (best.t >= 0 && (t > best.t || (t == best.t && i > best.object))) return;
    best.t = t;
    best.object = i;
    best.normal = glm::normalize(glm::transpose(glm::dmat3(inv)) * localNormal);
    best.shading = best.normal;
    glm::dvec3 shading = glm::transpose(glm::dmat3(inv)) * localShadingNormal;
    if (glm::dot(shading, shading) > 0) best.shading = glm::normalize(shading);
    best.frontFace =
        obj.type == ShapeType::Quad ? glm::dot(best.normal, direction) < 0 : front;
    best.tint = glm::dvec3(1);
    best.roughnessTexel = best.metalnessTexel = 1;
    best.triangle = h.triangle;  // textureAt reads the textures there
    best.weights = h.weights;
    best.error = kRounding * (maxMagnitude(origin) +
                              std::abs(t) * maxMagnitude(direction) + objectSize_[i]);
}

ReferenceHit ReferenceRenderer::traceLinear(const glm::dvec3& origin,
                                            const glm::dvec3& direction, double tMin,
                                            double tMax) const {
    ReferenceHit best;
    for (uint32_t i = 0; i < scene_.objects.size(); ++i)
        hitObject(i, origin, direction, tMin, tMax, best);
    return best;
}

void ReferenceRenderer::buildBvh() {
    std::vector<BoxItem> items;
    for (uint32_t i = 0; i < scene_.objects.size(); ++i) {
        const Object& o = scene_.objects[i];
        if (o.hidden) continue;
        BoxItem item{glm::dvec3(1e300), glm::dvec3(-1e300), {}, i};
        // The shape's own box: the unit sphere's, the unit quad's, a mesh's.
        glm::dvec3 lo(-1, o.type == ShapeType::Sphere ? -1 : 0, -1),
            hi(1, o.type == ShapeType::Sphere ? 1 : 0, 1);
        if (o.type == ShapeType::Mesh)
            lo = scene_.meshes[o.mesh]->lo, hi = scene_.meshes[o.mesh]->hi;
        for (int c = 0; c < 8; ++c) {
            glm::dvec3 corner(c & 1 ? hi.x : lo.x, c & 2 ? hi.y : lo.y,
                              c & 4 ? hi.z : lo.z);
            glm::dvec3 w = glm::dvec3(o.transform * glm::dvec4(corner, 1));
            item.lo = glm::min(item.lo, w);
            item.hi = glm::max(item.hi, w);
        }
        padBox(item);
        items.push_back(item);
    }
    buildTree(items, bvh_);
}

ReferenceRenderer::TriangleHit ReferenceRenderer::intersectMesh(const MeshData& mesh,
                                                                const glm::dvec3& o,
                                                                const glm::dvec3& d,
                                                                double tMin, double tMax,
                                                                const HitFilter& counts) {
    // [region watertight]
    // Woop, Benthin and Wald 2013: shear space so that the ray is the +z
    // axis through the origin; then a triangle is hit when the origin lies
    // inside its projection onto the xy plane, decided by the signs of three
    // 2D edge functions. An edge shared by two triangles gets the same
    // function (negated) from both, so a ray on the edge is inside one of
    // them, or both: it never passes between (watertight).
    int kz = std::abs(d.x) > std::abs(d.y) ? (std::abs(d.x) > std::abs(d.z) ? 0 : 2)
                                           : (std::abs(d.y) > std::abs(d.z) ? 1 : 2);
    int kx = (kz + 1) % 3, ky = (kx + 1) % 3;
    if (d[kz] < 0) std::swap(kx, ky);  // keep the winding
    double sx = d[kx] / d[kz], sy = d[ky] / d[kz], sz = 1.0 / d[kz];
    TriangleHit best;
    best.t = tMax;
    bool found = false;
    auto test = [&](uint32_t tri) {
        glm::dvec3 A = mesh.vertices[mesh.indices[3 * tri]] - o,
                   B = mesh.vertices[mesh.indices[3 * tri + 1]] - o,
                   C = mesh.vertices[mesh.indices[3 * tri + 2]] - o;
        double ax = A[kx] - sx * A[kz], ay = A[ky] - sy * A[kz];
        double bx = B[kx] - sx * B[kz], by = B[ky] - sy * B[kz];
        double cx = C[kx] - sx * C[kz], cy = C[ky] - sy * C[kz];
        double u = cx * by - cy * bx, v = ax * cy - ay * cx, w = bx * ay - by * ax;
        // on an edge: decide it exactly enough, in long double
        if (u == 0 || v == 0 || w == 0) {
            long double U = (long double)cx * by - (long double)cy * bx,
                        V = (long double)ax * cy - (long double)ay * cx,
                        W = (long double)bx * ay - (long double)by * ax;
            u = double(U), v = double(V), w = double(W);
        }
        // outside an edge
        if ((u < 0 || v < 0 || w < 0) && (u > 0 || v > 0 || w > 0)) return;
        double det = u + v + w;
        if (det == 0) return;  // seen edge-on
        double az = sz * A[kz], bz = sz * B[kz], cz = sz * C[kz];
        double t = (u * az + v * bz + w * cz) / det;
        if (!(t > tMin && t < best.t)) return;
        if (counts && !counts(tri, glm::dvec3(u, v, w) / det)) return;
        best = {t, tri, glm::dvec3(u, v, w) / det, det > 0};
        found = true;
    };
    // [end]
    traverseTree(mesh.bvh, o, d, tMin, [&] { return best.t; }, test);
    if (!found) best.t = -1;
    return best;
}

ReferenceHit ReferenceRenderer::trace(const glm::dvec3& origin,
                                      const glm::dvec3& direction, double tMin,
                                      double tMax) const {
    ReferenceHit best;
    traverseTree(
        bvh_, origin, direction, tMin, [&] { return best.t >= 0 ? best.t : tMax; },
        [&](uint32_t i) { hitObject(i, origin, direction, tMin, tMax, best); });
    return best;
}

glm::dvec3 ReferenceRenderer::sky(const glm::dvec3& dir) const {
    glm::dvec3 d = glm::normalize(dir);
    if (skyWidth_ == 0)
        return d.y >= 0 ? glm::mix(scene_.sky.horizon, scene_.sky.top, d.y)
                        : glm::mix(scene_.sky.horizon, scene_.sky.bottom, -d.y);
    double u = 0.5 + std::atan2(d.x, -d.z) / (2 * kPi);
    double v = std::acos(std::clamp(d.y, -1.0, 1.0)) / kPi;
    double x = u * skyWidth_ - 0.5, y = v * skyHeight_ - 0.5;
    double fx0 = std::floor(x), fy0 = std::floor(y);
    double fx = x - fx0, fy = y - fy0;
    auto texel = [&](long tx, long ty) {
        long w = skyWidth_, h = skyHeight_;
        tx = ((tx % w) + w) % w;
        ty = std::clamp(ty, 0L, h - 1);
        const double* p = &sky_[3 * (size_t(ty) * w + tx)];
        return glm::dvec3(p[0], p[1], p[2]);
    };
    long x0 = long(fx0), y0 = long(fy0);
    return glm::mix(glm::mix(texel(x0, y0), texel(x0 + 1, y0), fx),
                    glm::mix(texel(x0, y0 + 1), texel(x0 + 1, y0 + 1), fx), fy);
}

void ReferenceRenderer::cameraRay(uint32_t x, uint32_t y, uint32_t width, uint32_t height,
                                  glm::dvec3& origin, glm::dvec3& direction,
                                  glm::dvec2 offset) const {
    // A camera basis, not matrices: forward, right, up from look-at and up.
    const Camera& c = scene_.camera;
    glm::dvec3 forward = glm::normalize(c.lookAt - c.position);
    glm::dvec3 right = glm::normalize(glm::cross(forward, c.up));
    glm::dvec3 up = glm::cross(right, forward);
    double tanHalf = std::tan(glm::radians(c.fovYDeg) / 2),
           aspect = double(width) / height;
    double sx = ((x + offset.x) / width * 2 - 1) * tanHalf * aspect;
    double sy = (1 - (y + offset.y) / height * 2) * tanHalf;  // the top row looks up
    origin = c.position;
    direction = glm::normalize(forward + sx * right + sy * up);
}

double ReferenceRenderer::pixelSpread(uint32_t height) const {
    return std::atan(2 * std::tan(glm::radians(scene_.camera.fovYDeg) / 2) / height);
}

glm::dvec3 ReferenceRenderer::secondaryOrigin(const glm::dvec3& p, double error,
                                              const glm::dvec3& n) const {
    return p + error * n;
}

bool ReferenceRenderer::lightVisible(const glm::dvec3& from,
                                     const glm::dvec3& light) const {
    glm::dvec3 toLight = light - from;
    double d = glm::length(toLight);
    // as the GPU's, in double
    double shortBy = kRounding * std::max(maxMagnitude(from), maxMagnitude(light));
    return trace(from, toLight / d, 0.0, d - shortBy).t < 0;
}

}  // namespace rg
