#include "render/solids.h"

#include <cstddef>

namespace rtsph::render {

namespace {
Vec3f rotate(const std::array<float, 9>& r, const Vec3f& v) {
  return {r[0] * v.x + r[3] * v.y + r[6] * v.z, r[1] * v.x + r[4] * v.y + r[7] * v.z,
          r[2] * v.x + r[5] * v.y + r[8] * v.z};
}
constexpr float kQuad[6][2] = {{-1, -1}, {1, -1}, {1, 1}, {-1, -1}, {1, 1}, {-1, 1}};
}  // namespace

SolidPass::SolidPass() : program_({"solid.vert", "solid.frag"}) {
  glGenVertexArrays(1, &vao_);
  glGenBuffers(1, &vbo_);
  glBindVertexArray(vao_);
  glBindBuffer(GL_ARRAY_BUFFER, vbo_);
  const GLsizei stride = sizeof(Vertex);
  const std::size_t offs[4] = {offsetof(Vertex, pos), offsetof(Vertex, normal),
                               offsetof(Vertex, local), offsetof(Vertex, shape)};
  const GLint sizes[4] = {3, 3, 2, 4};
  for (GLuint i = 0; i < 4; ++i) {
    glEnableVertexAttribArray(i);
    glVertexAttribPointer(i, sizes[i], GL_FLOAT, GL_FALSE, stride, reinterpret_cast<void*>(offs[i]));
  }
  glBindVertexArray(0);
  glBindBuffer(GL_ARRAY_BUFFER, 0);
}

SolidPass::~SolidPass() {
  glDeleteVertexArrays(1, &vao_);
  glDeleteBuffers(1, &vbo_);
}

void SolidPass::build(int dim) {
  scratch_.clear();
  auto push = [&](const Vec3f& p, const Vec3f& n, float lx, float ly, float kind, float a, float b) {
    scratch_.push_back({{p.x, p.y, p.z}, {n.x, n.y, n.z}, {lx, ly}, {kind, a, b, 0}});
  };
  for (const SolidShape& s : solids_) {
    const Vec3f c = dim == 2 ? Vec3f{s.center.x, s.center.y, 0} : s.center;
    const Vec3f he = s.half_extents;
    if (dim == 2) {
      // A quad covering the shape; the fragment shader cuts the circle and shades the rim.
      const bool box = s.kind == SolidShape::Kind::Box;
      const float hx = box ? he.x : s.radius, hy = box ? he.y : s.radius;
      for (const auto& q : kQuad) {
        const Vec3f l{q[0] * hx, q[1] * hy, 0};
        push(c + (box ? rotate(s.rotation, l) : l), {0, 0, 1}, l.x, l.y, box ? 2.0f : 3.0f,
             box ? hx : s.radius, hy);
      }
    } else if (s.kind == SolidShape::Kind::Sphere) {
      for (const auto& q : kQuad) push(c, {0, 0, 1}, q[0], q[1], 1.0f, s.radius, 0);
    } else {
      for (int axis = 0; axis < 3; ++axis)
        for (float side : {-1.0f, 1.0f}) {
          const int a1 = (axis + 1) % 3, a2 = (axis + 2) % 3;
          Vec3f nl{};
          (axis == 0 ? nl.x : axis == 1 ? nl.y : nl.z) = side;
          const Vec3f n = rotate(s.rotation, nl);
          for (const auto& q : kQuad) {
            float l[3];
            l[axis] = side * he[axis];
            l[a1] = q[0] * he[a1];
            l[a2] = q[1] * he[a2];
            push(c + rotate(s.rotation, {l[0], l[1], l[2]}), n, 0, 0, 0.0f, 0, 0);
          }
        }
    }
  }
  built_dim_ = dim;
  vertices_ = static_cast<GLsizei>(scratch_.size());
  glBindBuffer(GL_ARRAY_BUFFER, vbo_);
  glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(scratch_.size() * sizeof(Vertex)),
               scratch_.empty() ? nullptr : scratch_.data(), GL_STREAM_DRAW);
  glBindBuffer(GL_ARRAY_BUFFER, 0);
}

bool SolidPass::draw(int dim, const Mat4& view, const Mat4& proj, bool ortho, const Rgb& color) {
  if (solids_.empty()) return false;
  if (built_dim_ != dim) build(dim);
  program_.use();
  glUniformMatrix4fv(program_.loc("u_view"), 1, GL_FALSE, view.data());
  glUniformMatrix4fv(program_.loc("u_proj"), 1, GL_FALSE, proj.data());
  glUniform1i(program_.loc("u_ortho"), ortho ? 1 : 0);
  glUniform3f(program_.loc("u_color"), color.r, color.g, color.b);
  glBindVertexArray(vao_);
  glDrawArrays(GL_TRIANGLES, 0, vertices_);
  glBindVertexArray(0);
  return true;
}

}  // namespace rtsph::render
