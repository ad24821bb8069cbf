#include "render/scene_lines.h"

#include <algorithm>
#include <cmath>

namespace rtsph::render {

namespace {

float nice_step(float extent) {
  float raw = std::max(extent, 1e-6f) / 10.0f;
  float p = std::pow(10.0f, std::floor(std::log10(raw)));
  float m = raw / p;
  return (m < 1.5f ? 1.0f : m < 3.5f ? 2.0f : m < 7.5f ? 5.0f : 10.0f) * p;
}

LineVertex at(LineVertex v, float x, float y, float z) {
  v.x = x;
  v.y = y;
  v.z = z;
  return v;
}

}  // namespace

void build_grid_lines(int dim, const Vec3f& lo, const Vec3f& hi, std::vector<LineVertex>* out) {
  const bool three = dim == 3;
  const Vec3f size = hi - lo;
  const float extent = std::max({size.x, size.y, three ? size.z : 0.0f, 1e-3f});
  const float step = nice_step(extent);
  const LineVertex base{0, 0, 0, 0.55f, 0.57f, 0.62f, three ? 0.35f : 0.18f};
  if (three) {
    const float cx = 0.5f * (lo.x + hi.x), cz = 0.5f * (lo.z + hi.z);
    const float half = std::ceil(1.5f * extent / step) * step;
    const float x0 = std::floor((cx - half) / step) * step;
    const float z0 = std::floor((cz - half) / step) * step;
    const int lines = static_cast<int>(std::lround(2 * half / step)) + 1;
    const float y = lo.y - 1e-4f * extent, end = lines * step;
    for (int i = 0; i <= lines; ++i) {
      const float x = x0 + i * step, z = z0 + i * step;
      out->insert(out->end(), {at(base, x, y, z0), at(base, x, y, z0 + end), at(base, x0, y, z),
                               at(base, x0 + end, y, z)});
    }
    return;
  }
  const float x0 = std::floor(lo.x / step) * step, x1 = std::ceil(hi.x / step) * step;
  const float y0 = std::floor(lo.y / step) * step, y1 = std::ceil(hi.y / step) * step;
  for (float x = x0; x <= x1 + 0.5f * step; x += step)
    out->insert(out->end(), {at(base, x, y0, 0), at(base, x, y1, 0)});
  for (float y = y0; y <= y1 + 0.5f * step; y += step)
    out->insert(out->end(), {at(base, x0, y, 0), at(base, x1, y, 0)});
}

void build_walls_2d(const Vec3f& lo, const Vec3f& hi, float t, std::vector<LineVertex>* out) {
  const LineVertex c{0, 0, 0, 0.55f, 0.6f, 0.68f, 0.55f};
  auto rect = [&](float ax, float ay, float bx, float by) {
    const LineVertex p0 = at(c, ax, ay, 0), p1 = at(c, bx, ay, 0), p2 = at(c, bx, by, 0),
                     p3 = at(c, ax, by, 0);
    out->insert(out->end(), {p0, p1, p2, p0, p2, p3});
  };
  rect(lo.x - t, lo.y - t, hi.x + t, lo.y);
  rect(lo.x - t, hi.y, hi.x + t, hi.y + t);
  rect(lo.x - t, lo.y, lo.x, hi.y);
  rect(hi.x, lo.y, hi.x + t, hi.y);
}

void build_walls_3d(const Vec3f& eye, const Vec3f& lo, const Vec3f& hi,
                    std::vector<LineVertex>* faces, std::vector<LineVertex>* edges) {
  const LineVertex fc{0, 0, 0, 0.62f, 0.72f, 0.85f, 0.10f};
  const LineVertex ec{0, 0, 0, 0.70f, 0.75f, 0.82f, 0.55f};
  auto corner = [&](int bits) {
    return Vec3f{bits & 1 ? hi.x : lo.x, bits & 2 ? hi.y : lo.y, bits & 4 ? hi.z : lo.z};
  };
  for (int axis = 0; axis < 3; ++axis)
    for (int side = 0; side < 2; ++side) {
      const float plane = side ? hi[axis] : lo[axis];
      const float e = eye[axis];
      const bool inside_sees = side ? e < plane : e > plane;
      if (!inside_sees) continue;
      const int a1 = (axis + 1) % 3, a2 = (axis + 2) % 3;
      const int pairs[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
      LineVertex q[4];
      for (int k = 0; k < 4; ++k) {
        const Vec3f p = corner((side << axis) | (pairs[k][0] << a1) | (pairs[k][1] << a2));
        q[k] = at(fc, p.x, p.y, p.z);
      }
      faces->insert(faces->end(), {q[0], q[1], q[2], q[0], q[2], q[3]});
    }
  for (int i = 0; i < 8; ++i)
    for (int axis = 0; axis < 3; ++axis)
      if (!(i & (1 << axis))) {
        const Vec3f p = corner(i), r = corner(i | (1 << axis));
        edges->push_back(at(ec, p.x, p.y, p.z));
        edges->push_back(at(ec, r.x, r.y, r.z));
      }
}

}  // namespace rtsph::render
