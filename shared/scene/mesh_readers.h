// What the mesh file readers share, inside scene/ only (chapter 12): each
// format's reader, and the decoding of the images they name.
#pragma once
#include "scene/mesh_file.h"

#include <string>
#include <vector>

namespace rg {

// Throws InputError "<path>: <what>": a mesh file's one-line refusal.
[[noreturn]] void refuseFile(const std::string& path, const std::string& what);

MeshFile loadObj(const std::string& path);                 // obj_file.cpp
MeshFile loadGltf(const std::string& path, bool binary);   // gltf_file.cpp

constexpr int kMaxTextureSide = 8192;
// An image file or the bytes of one, decoded to 8-bit RGBA; "" when it is fine.
std::string decodeImage(const unsigned char* bytes, int size, int& width, int& height,
                        std::vector<unsigned char>& rgba);
// The bytes of an image an OBJ's material names; throws InputError naming both.
std::vector<unsigned char> readImageFile(const std::string& meshPath,
                                         const std::string& image);

}  // namespace rg
