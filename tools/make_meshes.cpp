// Writes chapter 12's objects from the real world, procedurally (no
// downloaded assets), into the folder given: each glass is a closed,
// consistently wound surface, counter-clockwise seen from outside. Lengths
// are in millimetres, as an optician gives them.
//   lens.obj         biconvex BK7 lens, R = +-50 mm, centre thickness 5 mm, 30 mm across
//   prism.obj        60-degree prism, 30 mm sides, 30 mm tall (flat faces)
//   slab.obj         glass slab 40 x 30 x 10 mm (flat faces)
//   wine_glass.gltf  a lathe-turned wine glass, with its glass material (+ .bin)
//   tumbler.obj      a drinking glass: 60 mm across, 90 mm tall, 2.5 mm wall,
//                    8 mm base, its inner corner rounded (3 mm)
//   water.obj        the water in it, 52 mm deep: 0.3 mm into the glass all round,
//                    so no film of air is left between (chapter 13's priorities)
//   ice_cube.obj     a 22 mm ice cube
//   ring.obj         a ring, 100 mm across, 20 mm tall, 2 mm wall (chapter 14's
//                    mirror: the cardioid a cup throws)
//   icosphere_N.obj  the unit icosphere at levels 1-5 (smooth normals)
//   grid_box.obj     the cube [-1, 1]^3, each face a 32 x 32 grid of squares
//                    (chapter 12's leak measurement: flat faces, exact edges)
//   torus_1m.glb     a torus of 1,000,000 triangles (a big mesh, binary glTF)
//   tiles.glb        a tiled floor: a square with a base colour texture (an
//                    embedded PNG) repeated 10 times each way, opaque and open
//   far_floor.glb    the same tiles repeated 200 times each way (chapter 12's
//                    mip levels: a floor that reaches the horizon)
//   panel.glb        a painted metal panel: base colour, metal-roughness and normal
//                    textures (a window of bare metal, rivets, a raised rim)
//   etched_pane.glb  a pane of glass 1 x 1 x 0.02 (chapter 15's etched glass):
//                    its front etched (roughness texture) but for a clear border,
//                    a clear disc and a clear ring; standing on y = 0, facing +z
//   leaf.glb         a leaf on a card: a square whose texture's alpha cuts the
//                    leaf out (alphaMode MASK), with a round hole at its centre
#include "core/files.h"
#include "scene/mesh.h"

#include <nlohmann/json.hpp>
#include <stb_image_write.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <map>
#include <tuple>
#include <stdexcept>
#include <string>
#include <vector>

namespace {

constexpr double kPi = 3.14159265358979323846;

void writeText(const std::string& path, const std::string& text) { rg::writeFileAtomically(path, text.data(), text.size()); }

std::string toObj(const rg::Mesh& m, const std::string& comment) {
    std::string out = "# " + comment + "\n";
    char line[128];
    for (const glm::vec3& v : m.vertices) std::snprintf(line, sizeof line, "v %.9g %.9g %.9g\n", v.x, v.y, v.z), out += line;
    for (const glm::vec3& n : m.normals) std::snprintf(line, sizeof line, "vn %.9g %.9g %.9g\n", n.x, n.y, n.z), out += line;
    for (size_t t = 0; t < m.indices.size(); t += 3) {
        uint32_t a = m.indices[t] + 1, b = m.indices[t + 1] + 1, c = m.indices[t + 2] + 1;
        if (m.normals.empty()) std::snprintf(line, sizeof line, "f %u %u %u\n", a, b, c);
        else std::snprintf(line, sizeof line, "f %u//%u %u//%u %u//%u\n", a, a, b, b, c, c);
        out += line;
    }
    return out;
}

// A surface of revolution about +y: the profile (r, y) from the axis round
// to the axis, each point with its 2D outward normal; `segments` around.
// Points on the axis (r = 0) are one vertex each, so no triangle there is
// degenerate.
rg::Mesh lathe(const std::vector<glm::dvec2>& profile, const std::vector<glm::dvec2>& normals, int segments) {
    rg::Mesh m;
    std::vector<uint32_t> first(profile.size());
    for (size_t i = 0; i < profile.size(); ++i) {
        first[i] = uint32_t(m.vertices.size());
        int count = profile[i].x == 0 ? 1 : segments;
        for (int s = 0; s < count; ++s) {
            double a = 2 * kPi * s / segments, c = std::cos(a), sn = std::sin(a);
            m.vertices.push_back(glm::vec3(float(profile[i].x * c), float(profile[i].y), float(-profile[i].x * sn)));
            m.normals.push_back(glm::normalize(glm::vec3(float(normals[i].x * c), float(normals[i].y), float(-normals[i].x * sn))));
        }
    }
    auto at = [&](size_t i, int s) { return profile[i].x == 0 ? first[i] : first[i] + uint32_t(s % segments); };
    for (size_t i = 0; i + 1 < profile.size(); ++i) {
        if (profile[i] == profile[i + 1]) continue;  // a crease: the same point twice, with two normals
        for (int s = 0; s < segments; ++s) {
            uint32_t a = at(i, s), b = at(i, s + 1), c = at(i + 1, s), d = at(i + 1, s + 1);
            if (profile[i].x != 0) m.indices.insert(m.indices.end(), {a, c, b});
            if (profile[i + 1].x != 0) m.indices.insert(m.indices.end(), {b, c, d});
        }
    }
    // Outward: a positive enclosed volume (the divergence theorem); the
    // profile's direction decides the winding, so it is checked, not assumed.
    double volume = 0;
    for (size_t t = 0; t < m.indices.size(); t += 3)
        volume += glm::dot(glm::dvec3(m.vertices[m.indices[t]]),
                           glm::cross(glm::dvec3(m.vertices[m.indices[t + 1]]), glm::dvec3(m.vertices[m.indices[t + 2]])));
    if (volume < 0)
        for (size_t t = 0; t < m.indices.size(); t += 3) std::swap(m.indices[t + 1], m.indices[t + 2]);
    return m;
}

// Points of an arc of the circle (centre, radius) from angle a0 to a1, with
// outward normals (sign +1) or inward (-1).
void arc(std::vector<glm::dvec2>& p, std::vector<glm::dvec2>& n, glm::dvec2 centre, double radius, double a0, double a1,
         int steps, double sign) {
    for (int k = 0; k <= steps; ++k) {
        double a = a0 + (a1 - a0) * k / steps;
        glm::dvec2 dir(std::cos(a), std::sin(a));
        p.push_back(centre + radius * dir);
        n.push_back(sign * dir);
    }
}

// [region lens]
// Biconvex lens about the y axis, its profile from the axis out along the
// lower surface (a circle of radius R centred at y = R - t/2), up the short
// cylindrical rim, and back along the upper surface to the axis. Each
// point's normal is the surface's exact one, so the interpolated normals
// are the sphere's (a crease at both ends of the rim).
rg::Mesh lens(double R, double t, double aperture) {
    double reach = std::asin(aperture / R), halfRim = t / 2 - (R - std::sqrt(R * R - aperture * aperture));
    const int steps = 64;
    std::vector<glm::dvec2> p, n;
    for (int k = 0; k <= steps; ++k) {
        double a = reach * k / steps;
        p.push_back({R * std::sin(a), (R - t / 2) - R * std::cos(a)}), n.push_back({std::sin(a), -std::cos(a)});
    }
    p.push_back({aperture, -halfRim}), n.push_back({1, 0});
    p.push_back({aperture, halfRim}), n.push_back({1, 0});
    for (int k = steps; k >= 0; --k) {
        double a = reach * k / steps;
        p.push_back({R * std::sin(a), -(R - t / 2) + R * std::cos(a)}), n.push_back({std::sin(a), std::cos(a)});
    }
    p.front().x = p.back().x = 0;  // exactly on the axis
    return lathe(p, n, 256);
}
// [end]

// A flat-faced solid: triangles of the given vertices, no normals.
rg::Mesh prism(double side, double height) {
    rg::Mesh m;
    double r = side / std::sqrt(3.0);  // circumradius of the triangle
    for (int k = 0; k < 3; ++k) {
        double a = 2 * kPi * k / 3 + kPi / 2;
        m.vertices.push_back(glm::vec3(float(r * std::cos(a)), 0.0f, float(-r * std::sin(a))));
    }
    for (int k = 0; k < 3; ++k) m.vertices.push_back(m.vertices[k] + glm::vec3(0, float(height), 0));
    m.indices = {0, 2, 1, 3, 4, 5};  // bottom faces down, top up
    for (uint32_t k = 0; k < 3; ++k) {
        uint32_t a = k, b = (k + 1) % 3;
        m.indices.insert(m.indices.end(), {a, b, b + 3, a, b + 3, a + 3});
    }
    return m;
}

rg::Mesh box(glm::vec3 size) {
    rg::Mesh m;
    glm::vec3 h = size / 2.0f;
    for (int c = 0; c < 8; ++c) m.vertices.push_back({c & 1 ? h.x : -h.x, c & 2 ? h.y : -h.y, c & 4 ? h.z : -h.z});
    m.indices = {0, 2, 3, 0, 3, 1,   4, 5, 7, 4, 7, 6,   0, 1, 5, 0, 5, 4,
                 2, 6, 7, 2, 7, 3,   0, 4, 6, 0, 6, 2,   1, 3, 7, 1, 7, 5};
    return m;
}

// A wine glass: bowl (outer and inner wall), rim, stem and foot, one closed profile.
rg::Mesh wineGlass() {
    std::vector<glm::dvec2> p, n;
    auto point = [&](double r, double y, double nr, double ny) { p.push_back({r, y}), n.push_back(glm::normalize(glm::dvec2(nr, ny))); };
    point(0, 0, 0, -1);             // foot, underside, on the axis
    point(35, 0, 0, -1);
    point(35, 0, 1, 0);             // crease at the foot's edge
    point(35, 3, 1, 0.3);
    point(6, 6, 0.3, 1);
    point(4, 12, 1, 0);             // stem
    point(4, 80, 1, -0.3);
    arc(p, n, {0, 120}, 40, -kPi / 2 + 0.1, 0.35, 40, 1);   // bowl, outside, up to the rim
    glm::dvec2 rimOut = p.back();
    point(rimOut.x, rimOut.y, 0, 1);                        // the rim's top, a crease
    point(rimOut.x - 1.5, rimOut.y, 0, 1);
    point(rimOut.x - 1.5, rimOut.y, -1, 0);
    arc(p, n, {0, 120}, 38.5, 0.35, -kPi / 2, 40, -1);      // bowl, inside, down to the axis
    // The inside arc ends on the axis at y = 81.5, above the stem's top.
    p.back().x = 0;
    return lathe(p, n, 96);
}

// Chapter 13: a straight-sided drinking glass, one closed profile with creases.
rg::Mesh tumbler() {
    std::vector<glm::dvec2> p, n;
    auto point = [&](double r, double y, double nr, double ny) { p.push_back({r, y}), n.push_back({nr, ny}); };
    point(0, 0, 0, -1), point(30, 0, 0, -1);        // the base's underside
    point(30, 0, 1, 0), point(30, 90, 1, 0);        // outside wall
    point(30, 90, 0, 1), point(27.5, 90, 0, 1);     // rim
    point(27.5, 90, -1, 0);                         // inside wall, down to
    // A rounded inner corner, as real glass has: at a right-angled crease a ray
    // through the edge itself takes either face's normal, and its paths differ.
    arc(p, n, {24.5, 11}, 3, 0, -kPi / 2, 8, -1);
    point(0, 8, 0, 1);                              // the base's top
    return lathe(p, n, 128);
}

// The water in the tumbler: a closed cylinder from 0.3 mm inside the base
// to its surface at y = 60 mm, 0.3 mm into the wall.
rg::Mesh water() {
    std::vector<glm::dvec2> p, n;
    auto point = [&](double r, double y, double nr, double ny) { p.push_back({r, y}), n.push_back({nr, ny}); };
    point(0, 7.7, 0, -1), point(27.8, 7.7, 0, -1);
    point(27.8, 7.7, 1, 0), point(27.8, 60, 1, 0);
    point(27.8, 60, 0, 1), point(0, 60, 0, 1);
    return lathe(p, n, 128);
}

// A ring (a napkin ring, a cup without its base): a thin cylindrical shell
// of outer radius r, wall w, height h, closed at both ends.
rg::Mesh ring(double r, double w, double h) {
    std::vector<glm::dvec2> p, n;
    auto point = [&](double x, double y, double nx, double ny) { p.push_back({x, y}), n.push_back({nx, ny}); };
    point(r, 0, 0, -1), point(r - w, 0, 0, -1);          // the bottom
    point(r - w, 0, -1, 0), point(r - w, h, -1, 0);      // inside wall, facing the axis
    point(r - w, h, 0, 1), point(r, h, 0, 1);            // the top
    point(r, h, 1, 0), point(r, 0, 1, 0);                // outside wall
    point(r, 0, 0, -1);                                  // back to the bottom (a crease)
    return lathe(p, n, 256);
}

rg::Mesh torus(double major, double minor, int around, int across) {
    rg::Mesh m;
    for (int i = 0; i < around; ++i)
        for (int j = 0; j < across; ++j) {
            double u = 2 * kPi * i / around, v = 2 * kPi * j / across;
            glm::dvec3 c(std::cos(u), 0, -std::sin(u)), dir = std::cos(v) * c + std::sin(v) * glm::dvec3(0, 1, 0);
            m.vertices.push_back(glm::vec3(major * c + minor * dir));
            m.normals.push_back(glm::vec3(dir));
        }
    auto at = [&](int i, int j) { return uint32_t((i % around) * across + j % across); };
    for (int i = 0; i < around; ++i)
        for (int j = 0; j < across; ++j)
            m.indices.insert(m.indices.end(), {at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j), at(i + 1, j + 1), at(i, j + 1)});
    return m;
}

// A floor tile's texture: two stones in a 2 x 2 checker with grout lines, 8-bit sRGB.
// An image as PNG bytes (stb_image_write), to embed in a .glb.
std::vector<unsigned char> encodePng(int width, int height, int channels, const std::vector<unsigned char>& pixels) {
    std::vector<unsigned char> png;
    auto append = [](void* context, void* data, int bytes) {
        auto* out = static_cast<std::vector<unsigned char>*>(context);
        out->insert(out->end(), static_cast<unsigned char*>(data), static_cast<unsigned char*>(data) + bytes);
    };
    if (!stbi_write_png_to_func(append, &png, width, height, channels, pixels.data(), width * channels))
        throw std::runtime_error("cannot encode a PNG");
    return png;
}

std::vector<unsigned char> tilePng(int size) {
    std::vector<unsigned char> rgb(size_t(size) * size * 3);
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x) {
            int tx = x % (size / 2), ty = y % (size / 2), grout = size / 32;
            bool light = (x < size / 2) == (y < size / 2);
            unsigned char c[3] = {light ? (unsigned char)222 : (unsigned char)64, light ? (unsigned char)210 : (unsigned char)72,
                                  light ? (unsigned char)186 : (unsigned char)88};
            if (tx < grout || ty < grout) c[0] = c[1] = c[2] = 140;
            std::memcpy(&rgb[3 * (size_t(y) * size + x)], c, 3);
        }
    return encodePng(size, size, 3, rgb);
}

// A leaf on a transparent card (chapter 12's alpha test): RGBA, green where
// the leaf is (alpha 255), alpha 0 around it and in a round hole at its
// centre (radius 0.15 of the card), so that a ray through the middle of the
// card, and a shadow ray, pass.
std::vector<unsigned char> leafPng(int size) {
    std::vector<unsigned char> rgba(size_t(size) * size * 4);
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x) {
            double u = (x + 0.5) / size - 0.5, v = (y + 0.5) / size - 0.5;
            // the leaf: an ellipse along the card's diagonal, with a vein
            double a = (u + v) / std::sqrt(2.0), b = (u - v) / std::sqrt(2.0);
            bool leaf = a * a / (0.46 * 0.46) + b * b / (0.2 * 0.2) <= 1;
            bool hole = u * u + v * v <= 0.15 * 0.15;
            bool vein = std::abs(b) < 0.012;
            unsigned char* p = &rgba[4 * (size_t(y) * size + x)];
            p[0] = vein ? 150 : 40;
            p[1] = vein ? 190 : 140;
            p[2] = vein ? 90 : 40;
            p[3] = leaf && !hole ? 255 : 0;
        }
    return encodePng(size, size, 4, rgba);
}

// A material's texture: its slot ("baseColorTexture", "metallicRoughnessTexture", "normalTexture") and PNG.
struct TextureImage {
    std::string slot;
    std::vector<unsigned char> png;
};

// A painted metal panel (chapter 12's metal-roughness and normal textures), three
// images of size x size over the texture square: red paint (rough, not metal) with a
// round window of bare metal (radius 0.3 about the centre), polished in its left half
// and brushed (roughness 0.05) in its right; eight rivets and a raised rim round the
// window, in the normal texture only (the panel stays flat).
double panelHeight(double u, double v) {  // the relief the normal texture encodes, in texture units
    double du = u - 0.5, dv = v - 0.5, r = std::sqrt(du * du + dv * dv);
    double h = 0.0;
    double rim = std::abs(r - 0.315) / 0.015;  // a rounded rim, 0.03 wide
    if (rim < 1) h = std::max(h, 0.01 * std::sqrt(1 - rim * rim));
    for (int k = 0; k < 8; ++k) {  // rivets of radius 0.03 on a circle of 0.41
        double a = k * kPi / 4, x = u - 0.5 - 0.41 * std::cos(a), y = v - 0.5 - 0.41 * std::sin(a);
        double q = (x * x + y * y) / (0.03 * 0.03);
        if (q < 1) h = std::max(h, 0.03 * std::sqrt(1 - q));
    }
    return h;
}
std::vector<TextureImage> panelImages(int size) {
    std::vector<unsigned char> colour(size_t(size) * size * 3), metalRough(colour.size()), normal(colour.size());
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x) {
            double u = (x + 0.5) / size, v = (y + 0.5) / size;
            bool metal = std::hypot(u - 0.5, v - 0.5) < 0.3;
            unsigned char* c = &colour[3 * (size_t(y) * size + x)];
            c[0] = metal ? 200 : 170, c[1] = metal ? 200 : 30, c[2] = metal ? 205 : 25;
            unsigned char* mr = &metalRough[3 * (size_t(y) * size + x)];
            mr[0] = 255;  // R: occlusion in glTF's packing, not read
            mr[1] = metal ? (u < 0.5 ? 0 : 13) : 140;  // G: roughness 0, 0.05, 0.55
            mr[2] = metal ? 255 : 0;                   // B: metalness
            // the relief's slope by central differences; +y of the normal is the image's up (-v)
            double e = 1.0 / size;
            double dhdu = (panelHeight(u + e, v) - panelHeight(u - e, v)) / (2 * e);
            double dhdv = (panelHeight(u, v + e) - panelHeight(u, v - e)) / (2 * e);
            glm::dvec3 n = glm::normalize(glm::dvec3(-dhdu, dhdv, 1));
            for (int k = 0; k < 3; ++k) normal[3 * (size_t(y) * size + x) + k] = (unsigned char)std::lround((n[k] + 1) / 2 * 255);
        }
    return {{"baseColorTexture", encodePng(size, size, 3, colour)},
            {"metallicRoughnessTexture", encodePng(size, size, 3, metalRough)},
            {"normalTexture", encodePng(size, size, 3, normal)}};
}

// Etched glass (chapter 15): a pane's metal-roughness texture, G the roughness
// factor's multiplier: 1 (etched) over the pane's front but for a clear
// border 0.06 wide, a clear disc (radius 0.2 about the centre) and a clear
// ring (0.27 to 0.31); edges antialiased (4 x 4 points a texel).
double etchedAt(double u, double v) {
    double r = std::hypot(u - 0.5, v - 0.5);
    bool border = std::min(std::min(u, 1 - u), std::min(v, 1 - v)) < 0.06;
    bool clear = border || r < 0.2 || (r > 0.27 && r < 0.31);
    return clear ? 0.0 : 1.0;
}
std::vector<TextureImage> etchImages(int size) {
    std::vector<unsigned char> metalRough(size_t(size) * size * 3);
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x) {
            double etched = 0;
            for (int k = 0; k < 16; ++k)
                etched += etchedAt((x + (k % 4 + 0.5) / 4) / size, (y + (k / 4 + 0.5) / 4) / size) / 16;
            unsigned char* mr = &metalRough[3 * (size_t(y) * size + x)];
            mr[0] = 255;                                             // R: occlusion, not read
            mr[1] = (unsigned char)std::lround(etched * 255);        // G: roughness
            mr[2] = 0;                                               // B: not metal
        }
    return {{"metallicRoughnessTexture", encodePng(size, size, 3, metalRough)}};
}

// A box of glass w x h x t standing on y = 0, facing +z, each face its own
// four vertices (flat normals, counter-clockwise from outside). The front's
// texture coordinates span the texture (v down, as glTF's); every other face
// reads the texture's corner (the clear border).
rg::Mesh pane(double w, double h, double t) {
    rg::Mesh m;
    const glm::dvec3 X(1, 0, 0), Y(0, 1, 0), Z(0, 0, 1), centre(0, h / 2, 0), half(w / 2, h / 2, t / 2);
    // each face: its normal and two axes with u x v = normal
    const glm::dvec3 faces[6][3] = {{Z, X, Y}, {-Z, Y, X}, {X, Y, Z}, {-X, Z, Y}, {Y, Z, X}, {-Y, X, Z}};
    // the half-size along an axis (a face's normal may point down one)
    auto extent = [&](const glm::dvec3& axis) { return std::abs(glm::dot(axis, half)); };
    for (const auto& f : faces) {
        auto base = uint32_t(m.vertices.size());
        bool front = f[0] == Z;
        for (int c = 0; c < 4; ++c) {
            double a = (c == 1 || c == 2) ? 1 : -1, b = c >= 2 ? 1 : -1;
            glm::dvec3 p = centre + f[0] * extent(f[0]) + a * f[1] * extent(f[1]) + b * f[2] * extent(f[2]);
            m.vertices.push_back(glm::vec3(p));
            m.normals.push_back(glm::vec3(f[0]));
            m.texcoords.push_back(front ? glm::vec2(float(p.x / w + 0.5), float(1 - p.y / h)) : glm::vec2(0.01f, 0.01f));
        }
        m.indices.insert(m.indices.end(), {base, base + 1, base + 2, base, base + 2, base + 3});
    }
    return m;
}

// A square [-1, 1] x {0} x [-1, 1] facing up, its texture repeated `repeat` times each way.
rg::Mesh square(float repeat) {
    rg::Mesh m;
    m.vertices = {{-1, 0, -1}, {1, 0, -1}, {1, 0, 1}, {-1, 0, 1}};
    m.normals.assign(4, {0, 1, 0});
    m.texcoords = {{0, 0}, {repeat, 0}, {repeat, repeat}, {0, repeat}};
    m.indices = {0, 2, 1, 0, 3, 2};  // counter-clockwise seen from above
    return m;
}

// glTF 2.0: one mesh, one node, one material; the buffer beside (.gltf + .bin) or inside (.glb).
// With texture coordinates, each image becomes the material's texture in its slot (embedded PNGs).
void writeGltf(const std::string& path, const rg::Mesh& m, nlohmann::json material, bool binary,
               const std::vector<TextureImage>& images = {}) {
    std::vector<unsigned char> bin;
    auto append = [&](const void* data, size_t bytes) {
        const auto* b = static_cast<const unsigned char*>(data);
        bin.insert(bin.end(), b, b + bytes);
        while (bin.size() % 4) bin.push_back(0);
    };
    size_t vOffset = 0, vBytes = m.vertices.size() * 12;
    append(m.vertices.data(), vBytes);
    size_t nOffset = bin.size(), nBytes = m.normals.size() * 12;
    append(m.normals.data(), nBytes);
    size_t iOffset = bin.size(), iBytes = m.indices.size() * 4;
    append(m.indices.data(), iBytes);
    size_t tOffset = bin.size(), tBytes = m.texcoords.size() * 8;
    append(m.texcoords.data(), tBytes);
    std::vector<std::pair<size_t, size_t>> pngs;  // offset, bytes
    for (const TextureImage& image : images) {
        pngs.emplace_back(bin.size(), image.png.size());
        append(image.png.data(), image.png.size());
    }
    glm::vec3 lo(INFINITY), hi(-INFINITY);
    for (const glm::vec3& v : m.vertices) lo = glm::min(lo, v), hi = glm::max(hi, v);
    std::string binName = path.substr(path.find_last_of('/') + 1);
    binName = binName.substr(0, binName.find_last_of('.')) + ".bin";
    nlohmann::json buffer = {{"byteLength", bin.size()}};
    if (!binary) buffer["uri"] = binName;
    nlohmann::json j = {
        {"asset", {{"version", "2.0"}, {"generator", "RayGlass tools/make_meshes"}}},
        {"scene", 0},
        {"scenes", {{{"nodes", {0}}}}},
        {"nodes", {{{"mesh", 0}, {"name", "object"}}}},
        {"meshes", {{{"primitives", {{{"attributes", {{"POSITION", 0}, {"NORMAL", 1}}}, {"indices", 2}, {"material", 0}, {"mode", 4}}}}}}},
        {"materials", {material}},
        {"buffers", {buffer}},
        {"bufferViews", {{{"buffer", 0}, {"byteOffset", vOffset}, {"byteLength", vBytes}, {"target", 34962}},
                         {{"buffer", 0}, {"byteOffset", nOffset}, {"byteLength", nBytes}, {"target", 34962}},
                         {{"buffer", 0}, {"byteOffset", iOffset}, {"byteLength", iBytes}, {"target", 34963}}}},
        {"accessors", {{{"bufferView", 0}, {"componentType", 5126}, {"count", m.vertices.size()}, {"type", "VEC3"},
                        {"min", {lo.x, lo.y, lo.z}}, {"max", {hi.x, hi.y, hi.z}}},
                       {{"bufferView", 1}, {"componentType", 5126}, {"count", m.normals.size()}, {"type", "VEC3"}},
                       {{"bufferView", 2}, {"componentType", 5125}, {"count", m.indices.size()}, {"type", "SCALAR"}}}},
    };
    if (material.contains("extensions"))  // the material's, and no others
        for (const auto& [name, value] : material["extensions"].items()) j["extensionsUsed"].push_back(name);
    if (!m.texcoords.empty()) {
        j["meshes"][0]["primitives"][0]["attributes"]["TEXCOORD_0"] = 3;
        j["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", tOffset}, {"byteLength", tBytes}, {"target", 34962}});
        j["accessors"].push_back({{"bufferView", 3}, {"componentType", 5126}, {"count", m.texcoords.size()}, {"type", "VEC2"}});
    }
    for (size_t i = 0; i < images.size(); ++i) {
        j["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", pngs[i].first}, {"byteLength", pngs[i].second}});
        j["images"].push_back({{"bufferView", j["bufferViews"].size() - 1}, {"mimeType", "image/png"}});
        j["samplers"] = {{{"magFilter", 9729}, {"wrapS", 10497}, {"wrapT", 10497}}};  // linear, repeat
        j["textures"].push_back({{"source", i}, {"sampler", 0}});
        const std::string& slot = images[i].slot;
        nlohmann::json& owner = slot == "normalTexture" ? j["materials"][0] : j["materials"][0]["pbrMetallicRoughness"];
        owner[slot]["index"] = i;  // beside what the material gives (a normal texture's scale)
    }
    if (!binary) {
        rg::writeFileAtomically(path.substr(0, path.find_last_of('/') + 1) + binName, bin.data(), bin.size());
        writeText(path, j.dump(1) + "\n");
        return;
    }
    std::string text = j.dump();
    while (text.size() % 4) text += ' ';
    std::vector<unsigned char> glb;
    auto u32 = [&](uint32_t v) { glb.insert(glb.end(), reinterpret_cast<unsigned char*>(&v), reinterpret_cast<unsigned char*>(&v) + 4); };
    u32(0x46546C67), u32(2), u32(uint32_t(12 + 8 + text.size() + 8 + bin.size()));
    u32(uint32_t(text.size())), u32(0x4E4F534A);
    glb.insert(glb.end(), text.begin(), text.end());
    u32(uint32_t(bin.size())), u32(0x004E4942);
    glb.insert(glb.end(), bin.begin(), bin.end());
    rg::writeFileAtomically(path, glb.data(), glb.size());
}

nlohmann::json glassMaterial(const std::string& name, double ior) {
    return {{"name", name},
            {"pbrMetallicRoughness", {{"baseColorFactor", {1, 1, 1, 1}}, {"metallicFactor", 0.0}, {"roughnessFactor", 0.0}}},
            // a volume of glass, not a thin wall: KHR_materials_volume's thickness
            // (its value is a rasterizer's hint; the mesh itself bounds the glass)
            {"extensions", {{"KHR_materials_transmission", {{"transmissionFactor", 1.0}}},
                            {"KHR_materials_ior", {{"ior", ior}}},
                            {"KHR_materials_volume", {{"thicknessFactor", 1.0}}}}}};
}

}  // namespace

// The cube [-1, 1]^3 whose every face is an n x n grid of squares, two
// triangles each; a vertex where faces meet is one vertex (a closed mesh).
// Its coordinates are exact in float (n a power of two).
rg::Mesh gridBox(int n) {
    rg::Mesh m;
    std::map<std::tuple<double, double, double>, uint32_t> index;
    auto vertex = [&](glm::dvec3 p) {
        auto [it, added] = index.try_emplace({p.x, p.y, p.z}, uint32_t(m.vertices.size()));
        if (added) m.vertices.push_back(glm::vec3(p));
        return it->second;
    };
    // each face's normal and two axes with u x v = normal (counter-clockwise from outside)
    const glm::dvec3 X(1, 0, 0), Y(0, 1, 0), Z(0, 0, 1);
    const glm::dvec3 faces[6][3] = {{X, Y, Z}, {-X, Z, Y}, {Y, Z, X}, {-Y, X, Z}, {Z, X, Y}, {-Z, Y, X}};
    for (const auto& f : faces)
        for (int i = 0; i < n; ++i)
            for (int j = 0; j < n; ++j) {
                auto at = [&](int a, int b) { return vertex(f[0] + (-1.0 + 2.0 * a / n) * f[1] + (-1.0 + 2.0 * b / n) * f[2]); };
                uint32_t p = at(i, j), q = at(i + 1, j), r = at(i + 1, j + 1), s = at(i, j + 1);
                m.indices.insert(m.indices.end(), {p, q, r, p, r, s});
            }
    return m;
}

int main(int argc, char** argv) {
    if (argc != 2) {
        std::fprintf(stderr, "usage: make_meshes FOLDER\n");
        return 2;
    }
    std::string dir = argv[1];
    try {
        writeText(dir + "/lens.obj", toObj(lens(50, 5, 15), "biconvex lens, R = +-50 mm, centre thickness 5 mm, 30 mm across, axis y"));
        writeText(dir + "/prism.obj", toObj(prism(30, 30), "60-degree prism, 30 mm sides, 30 mm tall, standing on y = 0"));
        writeText(dir + "/slab.obj", toObj(box({40, 10, 30}), "glass slab 40 x 10 x 30 mm, centred"));
        writeGltf(dir + "/wine_glass.gltf", wineGlass(), glassMaterial("glass", 1.5), false);
        writeText(dir + "/tumbler.obj", toObj(tumbler(), "drinking glass, 60 mm across, 90 mm tall, 2.5 mm wall, 8 mm base, 3 mm inner fillet"));
        writeText(dir + "/water.obj", toObj(water(), "the water in tumbler.obj: y 7.7 to 60 mm, radius 27.8 mm"));
        writeText(dir + "/ice_cube.obj", toObj(box({22, 22, 22}), "ice cube, 22 mm, centred"));
        writeText(dir + "/ring.obj", toObj(ring(50, 2, 20), "ring, 100 mm across, 20 mm tall, 2 mm wall, on y = 0"));
        for (int level = 1; level <= 5; ++level)
            writeText(dir + "/icosphere_" + std::to_string(level) + ".obj",
                      toObj(rg::icosphere(level), "unit icosphere, level " + std::to_string(level)));
        writeText(dir + "/grid_box.obj", toObj(gridBox(32), "the cube [-1, 1]^3, each face a 32 x 32 grid"));
        writeGltf(dir + "/torus_1m.glb", torus(40, 12, 1000, 500), glassMaterial("glass", 1.5), true);
        nlohmann::json stone = {{"name", "stone tiles"},
                                {"pbrMetallicRoughness", {{"baseColorFactor", {0.85, 0.85, 0.85, 1}}, {"metallicFactor", 0.0},
                                                          {"roughnessFactor", 0.9}}}};
        writeGltf(dir + "/tiles.glb", square(10), stone, true, {{"baseColorTexture", tilePng(64)}});
        writeGltf(dir + "/far_floor.glb", square(200), stone, true, {{"baseColorTexture", tilePng(64)}});
        nlohmann::json leaf = {{"name", "leaf"}, {"alphaMode", "MASK"}, {"alphaCutoff", 0.5}, {"doubleSided", true},
                               {"pbrMetallicRoughness", {{"metallicFactor", 0.0}, {"roughnessFactor", 0.8}}}};
        nlohmann::json panel = {{"name", "painted metal"},
                                {"pbrMetallicRoughness", {{"metallicFactor", 1.0}, {"roughnessFactor", 1.0}}},
                                {"normalTexture", {{"scale", 1.0}}}};
        writeGltf(dir + "/panel.glb", square(1), panel, true, panelImages(256));
        writeGltf(dir + "/leaf.glb", square(1), leaf, true, {{"baseColorTexture", leafPng(128)}});
        nlohmann::json etched = glassMaterial("etched glass", 1.5);
        etched["pbrMetallicRoughness"]["roughnessFactor"] = 0.5;  // times the texture's G
        writeGltf(dir + "/etched_pane.glb", pane(1, 1, 0.02), etched, true, etchImages(256));
    } catch (const std::exception& e) {
        std::fprintf(stderr, "make_meshes: %s\n", e.what());
        return 1;
    }
    return 0;
}
