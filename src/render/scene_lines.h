#pragma once
// Line and translucent-triangle geometry of the frame around the fluid: the ground grid, the 2D
// wall band and the 3D container (far faces and edges). Plain vertex lists; Renderer draws them.
#include <vector>

#include "render/math.h"

namespace rtsph::render {

struct LineVertex {
  float x, y, z;
  float r, g, b, a;
};

/// Grid lines (GL_LINES): 3D, the floor plane under [lo, hi]; 2D, behind the particles.
void build_grid_lines(int dim, const Vec3f& lo, const Vec3f& hi, std::vector<LineVertex>* out);
/// 2D walls (GL_TRIANGLES): a translucent band of the given thickness around the domain.
void build_walls_2d(const Vec3f& lo, const Vec3f& hi, float thickness,
                    std::vector<LineVertex>* out);
/// 3D container: translucent faces on the far side of the box as seen from `eye` (triangles) and
/// the twelve edges (lines).
void build_walls_3d(const Vec3f& eye, const Vec3f& lo, const Vec3f& hi,
                    std::vector<LineVertex>* faces, std::vector<LineVertex>* edges);

}  // namespace rtsph::render
