#include "reference.h"

#include "interrupt.h"

#include "display.h"
#include "progress.h"
#include "rt_scene.h"
#include "sampling.h"

#include <algorithm>
#include <atomic>
#include <bit>
#include <chrono>
#include <cstdint>
#include <cmath>
#include <random>
#include <thread>

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
    if (obj.hidden) return;  // a copy of an earlier object (scene.cpp's rule)
    const glm::dmat4& inv = worldToObject_[i];
    glm::dvec3 o = glm::dvec3(inv * glm::dvec4(origin, 1.0));
    // t is the same in both spaces
    glm::dvec3 d = glm::dvec3(inv * glm::dvec4(direction, 0.0));
    double t = -1;
    glm::dvec3 localNormal, localShadingNormal(0), tint(1);
    bool front = true;
    if (obj.type == ShapeType::Sphere) {
        double t0, t1;
        if (!referenceUnitSphere(o, d, t0, t1)) return;
        if (t0 > tMin && t0 < tMax) t = t0;
        else if (t1 > tMin && t1 < tMax) { t = t1; front = false; }
        else return;
        localNormal = o + t * d;
    } else if (obj.type == ShapeType::Mesh) {
        TriangleHit h = intersectMesh(meshes_[obj.mesh], o, d, tMin, tMax);
        if (h.t < 0) return;
        t = h.t;
        front = h.front;
        const MeshData& mesh = meshes_[obj.mesh];
        const uint32_t* v = &mesh.indices[3 * h.triangle];
        localNormal = glm::cross(mesh.vertices[v[1]] - mesh.vertices[v[0]],
                                 mesh.vertices[v[2]] - mesh.vertices[v[0]]);
        if (!mesh.normals.empty())
            localShadingNormal = h.weights.x * mesh.normals[v[0]] +
                                 h.weights.y * mesh.normals[v[1]] +
                                 h.weights.z * mesh.normals[v[2]];
        int texture = scene_.materials[obj.material].texture;
        if (texture >= 0 && !mesh.texcoords.empty())
            tint = sampleTexture(*scene_.textures[texture],
                                 h.weights.x * mesh.texcoords[v[0]] +
                                     h.weights.y * mesh.texcoords[v[1]] +
                                     h.weights.z * mesh.texcoords[v[2]]);
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
    best.tint = tint;
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
                                                                double tMin,
                                                                double tMax) {
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

glm::dvec3 ReferenceRenderer::sampleTexture(const Texture& texture,
                                            const glm::dvec2& uv) {
    auto wrap = [](double u, TextureWrap mode) {  // into [0, 1]
        if (mode == TextureWrap::Clamp) return std::clamp(u, 0.0, 1.0);
        if (mode == TextureWrap::Mirror)
            return 1 - std::abs(u - 2 * std::floor(u / 2) - 1);
        return u - std::floor(u);
    };
    auto texel = [&](long x, long y) {
        long w = texture.width, h = texture.height;
        x = texture.wrapU == TextureWrap::Repeat ? ((x % w) + w) % w
                                                 : std::clamp(x, 0L, w - 1);
        y = texture.wrapV == TextureWrap::Repeat ? ((y % h) + h) % h
                                                 : std::clamp(y, 0L, h - 1);
        return glm::dvec3(texture.texels[size_t(y) * w + x]);
    };
    double x = wrap(uv.x, texture.wrapU) * texture.width,
           y = wrap(uv.y, texture.wrapV) * texture.height;
    if (texture.nearest) return texel(long(std::floor(x)), long(std::floor(y)));
    x -= 0.5;
    y -= 0.5;
    double x0 = std::floor(x), y0 = std::floor(y), fx = x - x0, fy = y - y0;
    long ix = long(x0), iy = long(y0);
    return glm::mix(glm::mix(texel(ix, iy), texel(ix + 1, iy), fx),
                    glm::mix(texel(ix, iy + 1), texel(ix + 1, iy + 1), fx), fy);
}

Material ReferenceRenderer::hitMaterial(const ReferenceHit& hit) const {
    Material m = scene_.materials[scene_.objects[hit.object].material];
    m.ka *= hit.tint;
    m.kd *= hit.tint;
    return m;
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

double referenceFresnel(int mode, double f0, double cosI, double n1, double n2) {
    double sin2T = (n1 / n2) * (n1 / n2) * std::max(0.0, 1 - cosI * cosI);  // Snell
    // total internal reflection
    if (sin2T >= 1) return 1;
    double cosT = std::sqrt(1 - sin2T);
    if (mode == 2) {  // unpolarized: the mean of the s and p reflectances
        double rs = (n1 * cosI - n2 * cosT) / (n1 * cosI + n2 * cosT);
        double rp = (n2 * cosI - n1 * cosT) / (n2 * cosI + n1 * cosT);
        return (rs * rs + rp * rp) / 2;
    }
    if (mode == 1) f0 = std::pow((n1 - n2) / (n1 + n2), 2);
    // Schlick leaving a denser medium uses the transmitted angle
    double c = n1 > n2 ? cosT : cosI;
    return f0 + (1 - f0) * std::pow(1 - c, 5);
}

namespace {
// How light divides where a ray meets material m (chapters 08-11), and the
// indices on both sides; n faces the ray.
struct Split {
    double reflected = 0, refracted = 0, local = 1, n1 = 1, n2 = 1;
    // the highlight's share: the opaque part's and a dielectric's F
    double highlight = 1;
};

Split splitAt(const ReferenceSettings& settings, const Material& m, double n1, double n2,
              double cosI) {
    Split s;
    s.n1 = n1;
    s.n2 = n2;
    s.reflected = m.reflectivity;
    if (settings.stage >= ReferenceStage::Fresnel) {
        double F = referenceFresnel(settings.fresnelMode, m.f0, cosI, s.n1, s.n2);
        s.reflected = m.transmission * F + (1 - m.transmission) * m.reflectivity;
        if (settings.stage >= ReferenceStage::Refraction)
            s.refracted = m.transmission * (1 - F);
        s.highlight = (1 - m.transmission) * (1 - m.reflectivity) + m.transmission * F;
    }
    s.local = 1 - s.reflected - s.refracted;
    // chapter 08: the thesis's mix
    if (settings.stage < ReferenceStage::Fresnel) s.highlight = s.local;
    return s;
}

// Chapters 08-12: air outside every material.
Split splitAt(const ReferenceSettings& settings, const Material& m, bool entering,
              double cosI) {
    return entering ? splitAt(settings, m, 1.0, m.ior, cosI)
                    : splitAt(settings, m, m.ior, 1.0, cosI);
}

// Chapter 13's media (written again from the rule on docs/13_real_glass.md,
// not from media.glsl): the medium at a place is the stack's entry of
// highest priority, of equal ones the last entered; -1 is air.
int mediumOf(const Scene& scene, const MediumStack& media) {
    int best = -1, bestPriority = -1;
    for (size_t k = media.materials.size(); k-- > 0;) {
        int priority = scene.materials[media.materials[k]].priority;
        if (priority > bestPriority)
            best = int(media.materials[k]), bestPriority = priority;
    }
    return best;
}
double mediumIor(const Scene& scene, int medium) {
    return medium < 0 ? 1.0 : scene.materials[medium].ior;
}
glm::dvec3 mediumAbsorption(const Scene& scene, int medium) {
    return medium < 0 ? glm::dvec3(0) : scene.materials[medium].absorption;
}
constexpr size_t kMediaDepth = 4;  // as the GPU's MEDIA_DEPTH
constexpr double kMinNm = 380, kMaxNm = 780;
constexpr int kMaxPasses = 256;    // as the GPU's MAX_PASSES

// Snell's law in vector form: t = eta d + (eta cos_i - cos_t) n, n facing
// the ray; false under total internal reflection.
bool refractDirection(const glm::dvec3& d, const glm::dvec3& n, double n1, double n2,
                      glm::dvec3& t) {
    double eta = n1 / n2, cosI = -glm::dot(n, d);
    double k = 1 - eta * eta * (1 - cosI * cosI);
    if (k < 0) return false;
    t = glm::normalize(eta * d + (eta * cosI - std::sqrt(k)) * n);
    return true;
}

glm::dvec3 reflectDirection(const glm::dvec3& d, const glm::dvec3& n) {
    return d - 2 * glm::dot(d, n) * n;
}

// Chapter 12's rules for a mesh's two normals (shaders/common/ray_tree.glsl):
// a direction found with the shading normal ns that lands on the wrong
// side of the flat triangle (normal n, facing the ray) is found with n.
glm::dvec3 reflectSides(const glm::dvec3& d, const glm::dvec3& n, const glm::dvec3& ns) {
    glm::dvec3 r = reflectDirection(d, ns);
    return glm::dot(r, n) > 0 ? r : reflectDirection(d, n);
}
bool refractSides(const glm::dvec3& d, const glm::dvec3& n, const glm::dvec3& ns,
                  double n1, double n2, glm::dvec3& t) {
    if (refractDirection(d, ns, n1, n2, t) && glm::dot(t, n) < 0) return true;
    return refractDirection(d, n, n1, n2, t);
}

// The normals of a hit facing the ray: geometric n, and the shading normal
// turned with it, or n where it faces away (raygen_common.glsl's facingShading).
void facingNormals(const ReferenceHit& hit, const glm::dvec3& direction, glm::dvec3& n,
                   glm::dvec3& ns) {
    bool front = glm::dot(hit.normal, direction) < 0;
    n = front ? hit.normal : -hit.normal;
    ns = front ? hit.shading : -hit.shading;
    if (glm::dot(ns, direction) >= 0) ns = n;
}
}  // namespace

// [region path_wavelength]
double referencePathWavelength(uint32_t x, uint32_t y, uint32_t first, uint32_t k) {
    // PCG (Jarzynski and Olano 2020), as sampling.glsl's pcgHash
    auto hash = [](uint32_t v) {
        uint32_t state = v * 747796405u + 2891336453u;
        uint32_t word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
        return (word >> 22u) ^ word;
    };
    uint32_t reversed = 0;  // k's bits mirrored: the radical inverse
    for (int b = 0; b < 32; ++b) reversed |= ((k >> b) & 1u) << (31 - b);
    uint32_t seed = hash(x + hash(y + hash(first)));
    double u = double(reversed >> 8) / 16777216.0 + double(seed >> 8) / 16777216.0;
    return kMinNm + (kMaxNm - kMinNm) * (u - std::floor(u));
}
// [end]

// [region spectral_weight]
glm::dvec3 referenceSpectralWeight(double nm) {
    auto lobe = [](double x, double peak, double below, double above) {
        double t = (x - peak) / (x < peak ? below : above);
        return std::exp(-0.5 * t * t);
    };
    // CIE XYZ (Wyman, Sloan and Shirley 2013), then XYZ to linear sRGB
    auto srgb = [&](double x) {
        glm::dvec3 xyz(
            1.056 * lobe(x, 599.8, 37.9, 31.0) + 0.362 * lobe(x, 442.0, 16.0, 26.7) -
                0.065 * lobe(x, 501.1, 20.4, 26.2),
            0.821 * lobe(x, 568.8, 46.9, 40.5) + 0.286 * lobe(x, 530.9, 16.3, 31.1),
            1.217 * lobe(x, 437.0, 11.8, 36.0) + 0.681 * lobe(x, 459.0, 26.0, 13.8));
        return glm::dvec3(3.2404542 * xyz.x - 1.5371385 * xyz.y - 0.4985314 * xyz.z,
                          -0.9692660 * xyz.x + 1.8760108 * xyz.y + 0.0415560 * xyz.z,
                          0.0556434 * xyz.x - 0.2040259 * xyz.y + 1.0572252 * xyz.z);
    };
    static const glm::dvec3 mean = [&] {  // over the range, by a fine midpoint rule
        glm::dvec3 sum(0);
        const int steps = 40000;
        for (int k = 0; k < steps; ++k)
            sum += srgb(kMinNm + (kMaxNm - kMinNm) * (k + 0.5) / steps);
        return sum / double(steps);
    }();
    return srgb(nm) / mean;
}
// [end]

glm::dvec3 ReferenceRenderer::localShading(const ReferenceSettings& settings,
                                           const Material& m, const glm::dvec3& p,
                                           double error, const glm::dvec3& n,
                                           const glm::dvec3& ns, const glm::dvec3& v,
                                           double local, double highlight) const {
    glm::dvec3 color = local * m.ka * scene_.ambient;  // 3.1
    if (settings.stage == ReferenceStage::Ambient) return color;
    glm::dvec3 from = secondaryOrigin(p, error, n);
    for (const PointLight& light : scene_.lights) {  // 3.2 and 3.3
        glm::dvec3 l = glm::normalize(light.position - p);
        double ndotl = glm::dot(ns, l);
        if (ndotl <= 0) continue;
        glm::dvec3 added = local * light.intensity * m.kd * ndotl;
        if (settings.stage != ReferenceStage::Diffuse) {
            glm::dvec3 h = glm::normalize(l + v);
            added += highlight * light.intensity * m.ks *
                     std::pow(std::max(0.0, glm::dot(ns, h)), m.shininess);
            // As the GPU (shading.glsl's MIN_LIGHT): a light adding less than
            // 1e-4 is left out, as a branch carrying less is not traced.
            if (std::max({added.r, added.g, added.b}) < 1e-4) continue;
        }
        if (lightVisible(from, light.position)) color += added;
    }
    return color;
}

glm::dvec3 ReferenceRenderer::radiance(const ReferenceSettings& settings,
                                       const glm::dvec3& origin,
                                       const glm::dvec3& direction, int depth,
                                       const glm::dvec3& throughput) const {
    int passes = 0;
    return radiance(settings, origin, direction, depth, throughput, MediumStack{},
                    passes);
}

glm::dvec3 ReferenceRenderer::radiance(const ReferenceSettings& settings,
                                       const glm::dvec3& origin,
                                       const glm::dvec3& direction, int depth,
                                       const glm::dvec3& throughput,
                                       const MediumStack& media, int& passes) const {
    // depth 0: a camera ray
    ReferenceHit hit = trace(origin, direction, depth == 0 ? eyeTmin() : 0.0, 1e300);
    bool nested = settings.stage == ReferenceStage::Media;
    // Chapter 13: Beer-Lambert along the way, in the medium the ray is in.
    int here = nested ? mediumOf(scene_, media) : -1;  // -1: air
    glm::dvec3 kept(1), sigma = mediumAbsorption(scene_, here);
    for (int c = 0; c < 3; ++c)
        if (sigma[c] > 0) kept[c] = hit.t < 0 ? 0.0 : std::exp(-sigma[c] * hit.t);
    if (hit.t < 0) return kept * sky(direction);
    glm::dvec3 n, ns;  // toward the ray's origin: geometric, shading
    facingNormals(hit, direction, n, ns);
    if (settings.stage == ReferenceStage::Normals) return 0.5 * n + 0.5;
    const Material m = hitMaterial(hit);  // a mesh's texture tints it (chapter 12)
    glm::dvec3 p = origin + hit.t * direction;
    glm::dvec3 v = -direction;
    if (settings.stage <= ReferenceStage::Specular)
        return localShading(settings, m, p, hit.error, n, n, v);

    // How the light divides at this surface (chapters 08-10).
    bool entering = hit.frontFace;
    // air outside (chapter 10)
    double n1 = entering ? 1.0 : m.ior, n2 = entering ? m.ior : 1.0;
    const glm::dvec3 arriving = throughput * kept;
    MediumStack beyond = media;  // chapter 13: the media of a ray that crosses here
    if (nested && m.transmission > 0) {
        uint32_t material = scene_.objects[hit.object].material;
        int from = here;
        if (entering) {
            beyond.materials.push_back(material);
            if (beyond.materials.size() > kMediaDepth)
                beyond.materials.erase(beyond.materials.begin());
        } else {
            auto it =
                std::find(beyond.materials.rbegin(), beyond.materials.rend(), material);
            if (it != beyond.materials.rend())
                beyond.materials.erase(std::next(it).base());
            // leaving what it never entered: chapter 10's view
            else from = int(material);
        }
        int to = mediumOf(scene_, beyond);
        n1 = mediumIor(scene_, from), n2 = mediumIor(scene_, to);
        auto dispersionOf = [&](int k) {
            return k < 0 ? std::pair(Glass::None, 0.0)
                         : std::pair(scene_.materials[k].glass,
                                     scene_.materials[k].dispersion);
        };
        if (n1 == n2 && mediumAbsorption(scene_, from) == mediumAbsorption(scene_, to) &&
            dispersionOf(from) == dispersionOf(to)) {  // no surface here
            if (passes++ >= kMaxPasses) return glm::dvec3(0);
            return kept * radiance(settings, secondaryOrigin(p, hit.error, -n), direction,
                                   depth, arriving, beyond, passes);
        }
        const auto none = std::pair(Glass::None, 0.0);
        if (dispersionOf(from) != none || dispersionOf(to) != none) {
            if (media.wavelength == 0) {
                // The first dispersive surface of this path: from here on its light
                // depends on the wavelength. The same ray again at each wavelength.
                MediumStack at = media;
                if (settings.wavelength >= kMinNm || !media.wavelengths) {
                    at.wavelength =
                        settings.wavelength >= kMinNm ? settings.wavelength : 587.5618;
                    return radiance(settings, origin, direction, depth, throughput, at,
                                    passes);
                }
                glm::dvec3 sum(0);
                for (double nm : *media.wavelengths) {
                    at.wavelength = nm;
                    glm::dvec3 w = referenceSpectralWeight(nm);
                    int passesAt = passes;
                    sum += w * radiance(settings, origin, direction, depth,
                                        throughput * w, at, passesAt);
                }
                return sum / double(media.wavelengths->size());
            }
            auto indexOf = [&](int k) {
                return k < 0 ? 1.0 : indexAt(scene_.materials[k], media.wavelength);
            };
            n1 = indexOf(from), n2 = indexOf(to);
        }
    }
    Split split = splitAt(settings, m, n1, n2, glm::dot(ns, v));
    double reflected = split.reflected, refracted = split.refracted;
    glm::dvec3 color(0);
    if (split.highlight > 0)
        color += localShading(settings, m, p, hit.error, n, ns, v, split.local,
                              split.highlight);
    if (depth >= settings.maxDepth) return kept * color;
    constexpr double kMinThroughput = 1e-4;  // as the GPU's ray tree (chapter 10)
    auto strongEnough = [&](double w) {
        glm::dvec3 t = arriving * w;
        return settings.stage < ReferenceStage::Refraction ||
               std::max({t.r, t.g, t.b}) >= kMinThroughput;
    };
    glm::dvec3 t;
    if (refracted > 0 && strongEnough(refracted)) {
        if (refractSides(direction, n, ns, split.n1, split.n2, t))
            color +=
                refracted * radiance(settings, secondaryOrigin(p, hit.error, -n), t,
                                     depth + 1, arriving * refracted, beyond, passes);
        else
            reflected += refracted;  // a mesh's flat triangle reflects it all
    }
    if (reflected > 0 && strongEnough(reflected)) {
        glm::dvec3 r = reflectSides(direction, n, ns);
        color += reflected * radiance(settings, secondaryOrigin(p, hit.error, n), r,
                                      depth + 1, arriving * reflected, media, passes);
    }
    return kept * color;
}

// [region reference_footprint]
glm::dvec3 ReferenceRenderer::shade(const ReferenceSettings& settings, uint32_t x,
                                    uint32_t y, uint32_t width, uint32_t height,
                                    double* stdError) const {
    if (!settings.antialias)
        return shadeRay(settings, x, y, width, height, glm::dvec2(0.5), -1, stdError);
    // --antialias: the mean over the points of the pixel the GPU's frames
    // sampled (sampling.glsl's, compiled as C++), one camera ray each.
    uint32_t frames = std::max(1u, settings.frames);
    glm::dvec3 sum(0);
    double errorSq = 0;
    for (uint32_t k = 0; k < frames; ++k) {
        glm::dvec2 offset(shader::pixelJitter(shader::uvec2(x, y), k));
        double e = 0;
        sum += shadeRay(settings, x, y, width, height, offset, int(k), &e);
        errorSq += e * e;
    }
    // of a mean of independent estimates
    if (stdError) *stdError = std::sqrt(errorSq) / frames;
    return sum / double(frames);
}
// [end]

glm::dvec3 ReferenceRenderer::shadeRay(const ReferenceSettings& settings, uint32_t x,
                                       uint32_t y, uint32_t width, uint32_t height,
                                       glm::dvec2 offset, int frame,
                                       double* stdError) const {
    glm::dvec3 origin, direction;
    cameraRay(x, y, width, height, origin, direction, offset);
    if (stdError) *stdError = 0;
    // chapter 13: the eye may be inside a medium
    if (settings.stage == ReferenceStage::Media) {
        MediumStack eye;
        if (scene_.cameraMedium >= 0)
            eye.materials.push_back(uint32_t(scene_.cameraMedium));
        // the GPU's, frame after frame (one frame's: that frame's)
        std::vector<double> wavelengths;
        for (uint32_t k = 0; k < std::max(1u, settings.frames); ++k)
            if (frame < 0 || int(k) == frame)
                wavelengths.push_back(
                    referencePathWavelength(x, y, settings.firstFrame, k));
        eye.wavelengths = &wavelengths;
        int passes = 0;
        return radiance(settings, origin, direction, 0, glm::dvec3(1.0), eye, passes);
    }
    if (settings.stage != ReferenceStage::Rough)
        return radiance(settings, origin, direction, 0, glm::dvec3(1.0));

    // Chapter 11: the first surface's mirror branch becomes the mean over a
    // cone of directions. Same split and cone as the GPU; the integral is
    // estimated with many stratified samples from this code's own generator.
    ReferenceHit hit = trace(origin, direction, eyeTmin(), 1e300);
    if (hit.t < 0) return sky(direction);
    const Material m = hitMaterial(hit);  // a mesh's texture tints it (chapter 12)
    glm::dvec3 n, ns;
    facingNormals(hit, direction, n, ns);
    if (m.roughness <= 0 || settings.maxDepth == 0)
        return radiance(settings, origin, direction, 0, glm::dvec3(1.0));
    glm::dvec3 p = origin + hit.t * direction, v = -direction;
    bool entering = hit.frontFace;
    Split split = splitAt(settings, m, entering, glm::dot(ns, v));
    double reflected = split.reflected, refracted = split.refracted;
    glm::dvec3 color(0);
    if (split.highlight > 0)
        color += localShading(settings, m, p, hit.error, n, ns, v, split.local,
                              split.highlight);
    if (refracted >= 1e-4) {
        glm::dvec3 t;
        if (refractSides(direction, n, ns, split.n1, split.n2, t))
            color += refracted * radiance(settings, secondaryOrigin(p, hit.error, -n), t,
                                          1, glm::dvec3(refracted));
        else
            reflected += refracted;
    }
    if (reflected < 1e-4) return color;
    glm::dvec3 mirror = reflectSides(direction, n, ns);
    // A basis around the mirror direction, and the cone of half-angle roughness * pi/2.
    glm::dvec3 helper =
        std::abs(mirror.x) < 0.5 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
    glm::dvec3 t1 = glm::normalize(glm::cross(helper, mirror)),
               t2 = glm::cross(mirror, t1);
    double cosMax = std::cos(m.roughness * kPi / 2);
    int side = std::max(1, int(std::lround(std::sqrt(double(settings.samples)))));
    std::mt19937_64 rng(0x9E3779B97F4A7C15ull ^ (uint64_t(y) << 32 | x) ^
                        (settings.seed * 0xD1B54A32D192ED03ull) ^
                        // each antialiased ray its own
                        (uint64_t(frame + 1) * 0x8CB92BA72F3D8DD7ull));
    std::uniform_real_distribution<double> uniform(0.0, 1.0);
    glm::dvec3 from = secondaryOrigin(p, hit.error, n), sum(0), sumSq(0);
    for (int j = 0; j < side; ++j)
        for (int i = 0; i < side; ++i) {
            double u1 = (i + uniform(rng)) / side, u2 = (j + uniform(rng)) / side;
            double cosTheta = 1 - u1 * (1 - cosMax),
                   sinTheta = std::sqrt(std::max(0.0, 1 - cosTheta * cosTheta));
            glm::dvec3 d = glm::normalize(sinTheta * std::cos(2 * kPi * u2) * t1 +
                                          sinTheta * std::sin(2 * kPi * u2) * t2 +
                                          cosTheta * mirror);
            glm::dvec3 value(0);  // below the surface: absorbed
            if (glm::dot(d, n) > 0)
                value = radiance(settings, from, d, 1, glm::dvec3(reflected));
            sum += value;
            sumSq += value * value;
        }
    double count = double(side) * side;
    glm::dvec3 mean = sum / count,
               variance = (sumSq / count - mean * mean) * (count / (count - 1));
    if (stdError)  // of independent samples: stratification makes the true error smaller
        *stdError =
            reflected *
            std::sqrt(std::max(0.0, (variance.r + variance.g + variance.b) / 3) / count);
    return color + reflected * mean;
}

FloatImage ReferenceRenderer::render(const ReferenceSettings& settings, uint32_t width,
                                     uint32_t height) const {
    FloatImage image{width, height, std::vector<float>(size_t(width) * height * 4, 1.0f)};
    unsigned threads = std::max(1u, std::thread::hardware_concurrency());
    std::vector<std::thread> workers;
    std::atomic<uint32_t> rowsDone{0};
    for (unsigned t = 0; t < threads; ++t)
        workers.emplace_back([&, t] {
            for (uint32_t y = t; y < height; y += threads, ++rowsDone)
                // Ctrl-C: the rest stays unset
                for (uint32_t x = 0; x < width && !interrupted(); ++x) {
                    double stdError = 0;
                    glm::dvec3 c = shade(settings, x, y, width, height, &stdError) *
                                   settings.exposure;
                    float* p = &image.rgba[4 * (size_t(y) * width + x)];
                    p[0] = float(c.r), p[1] = float(c.g), p[2] = float(c.b);
                    if (settings.stage == ReferenceStage::Rough)
                        p[3] = float(stdError * settings.exposure);
                }
        });
    Progress progress("CPU reference", height);  // on a terminal only
    while (rowsDone.load() < height) {
        progress.update(rowsDone.load());
        std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    for (auto& w : workers) w.join();
    return image;
}

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
