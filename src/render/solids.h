#pragma once
// Obstacles drawn from their geometry rather than from their boundary particles: 3D boxes as lit
// meshes (per-face normals), 3D spheres as one ray-cast impostor each (true depth, Blinn-Phong
// as the particles), 2D rectangles and circles as filled shapes with a darkened rim. All solids
// go out in one draw call; the vertices (a few dozen per solid) are rebuilt on upload.
#include <epoxy/gl.h>

#include <array>
#include <cstddef>
#include <vector>

#include "render/colormap.h"
#include "render/math.h"
#include "render/shader.h"

namespace rtsph::render {

/// A rigid solid in world coordinates, filled by the app from the scene and the current pose
/// (the render layer knows nothing of the solver). 2D: Box is a rectangle, Sphere a circle,
/// both in the z = 0 plane, rotated about z.
struct SolidShape {
  enum class Kind { Box, Sphere };
  Kind kind = Kind::Box;
  Vec3f center{};
  /// Body → world rotation, column-major: columns are the body axes in world coordinates.
  std::array<float, 9> rotation{1, 0, 0, 0, 1, 0, 0, 0, 1};
  Vec3f half_extents{0.1f, 0.1f, 0.1f};  // m, Box
  float radius = 0.1f;                   // m, Sphere
};

class SolidPass {
 public:
  SolidPass();  // needs a current GL context
  ~SolidPass();
  SolidPass(const SolidPass&) = delete;
  SolidPass& operator=(const SolidPass&) = delete;

  void set(const std::vector<SolidShape>& solids) {
    solids_ = solids;
    built_dim_ = 0;
  }
  std::size_t count() const { return solids_.size(); }
  /// Draws every solid with one call (dim 2: rectangles and circles), depth-tested against
  /// whatever is in the depth buffer. Returns false (drawing nothing) when there are none.
  bool draw(int dim, const Mat4& view, const Mat4& proj, bool ortho, const Rgb& color);

 private:
  struct Vertex {
    float pos[3];     // world (sphere: its centre; the vertex shader spreads the quad)
    float normal[3];  // world, box faces
    float local[2];   // 2D: body-frame offset from the centre (m); sphere: quad corner in [-1,1]²
    float shape[4];   // kind (0 box, 1 sphere, 2 rectangle, 3 circle), then sizes (m)
  };
  void build(int dim);  // vertices of every solid into the buffer
  Program program_;
  GLuint vao_ = 0, vbo_ = 0;
  GLsizei vertices_ = 0;
  int built_dim_ = 0;  // dimension the buffer was built for; 0 = stale
  std::vector<SolidShape> solids_;
  std::vector<Vertex> scratch_;
};

}  // namespace rtsph::render
