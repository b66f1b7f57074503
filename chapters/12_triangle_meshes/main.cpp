// Chapter 12 - Triangle meshes (past the thesis: its acceleration structures
// of vertices, 2.2.1, with the pipeline's built-in triangle test, 2.2.3).
// Scenes may now place glTF and OBJ files ({"type": "mesh", "file": ...}):
// each mesh becomes one triangle BLAS, built from vertex and index buffers
// that the closest-hit shader then reads by device address
// (shaders/common/mesh.rchit). Shading is chapter 11's, with two rules that
// a mesh needs: the side a ray enters from is the hit kind (the winding),
// and a direction found with the interpolated normal that lands on the
// wrong side of the flat triangle is found again with the triangle's own
// normal (shaders/common/ray_tree.glsl). Everything else of chapters 04-11
// works on meshes and spheres together.
#include "chapter/rt_options.h"

int main(int argc, char** argv) {
    return rg::runRtChapter(argc, argv, {
        .name = "12_triangle_meshes",
        .description = "RayGlass chapter 12: triangle meshes from glTF and OBJ files,"
                       " watertight glass",
        .title = "RayGlass 12: triangle meshes",
        .stage = rg::ReferenceStage::Rough,
        // The shading is chapter 11's; what is new is the geometry.
        .raygenFolder = "11_rough",
        .meshes = true,
        // A lens, a prism, a slab and a wine glass (tools/make_meshes.cpp).
        .scene = "meshes",
        .options = [](rg::Params& params, rg::RtChapterSettings& s) {
            rg::addDepthOption(params, s, 6);
            rg::addFresnelOption(params, s);
            rg::addRoughOptions(params, s);
        },
    });
}
