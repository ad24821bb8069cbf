#include "render/snapshot.h"

namespace rtsph::render {

namespace {
template <class T>
void copy_array(std::vector<T>& dst, const T* src, std::size_t n) {
  if (!src) {
    dst.clear();
    return;
  }
  dst.assign(src, src + n);
}
}  // namespace

void ParticleSnapshot::copy_from(const ParticleView& f, const BoundaryView* b) {
  dim = f.dim;
  for (int k = 0; k < 3; ++k) {
    copy_array(x[k], k < f.dim ? f.x[k] : nullptr, f.count);
    copy_array(v[k], k < f.dim ? f.v[k] : nullptr, f.count);
  }
  copy_array(density, f.density, f.count);
  copy_array(pressure, f.pressure, f.count);
  if (b) {
    for (int k = 0; k < 3; ++k) copy_array(bx[k], k < b->dim ? b->x[k] : nullptr, b->count);
    copy_array(owner, b->owner, b->count);
  }
}

ParticleView ParticleSnapshot::fluid() const {
  ParticleView p;
  p.dim = dim;
  p.count = x[0].size();
  for (int k = 0; k < 3; ++k) {
    p.x[k] = x[k].empty() ? nullptr : x[k].data();
    p.v[k] = v[k].empty() ? nullptr : v[k].data();
  }
  p.density = density.empty() ? nullptr : density.data();
  p.pressure = pressure.empty() ? nullptr : pressure.data();
  return p;
}

BoundaryView ParticleSnapshot::boundary() const {
  BoundaryView b;
  b.dim = dim;
  b.count = owner.size();
  for (int k = 0; k < 3; ++k) b.x[k] = bx[k].empty() ? nullptr : bx[k].data();
  b.owner = owner.empty() ? nullptr : owner.data();
  return b;
}

}  // namespace rtsph::render
