#include "core/particles.h"

#include <cstring>

namespace rtsph {

namespace {
template <class T>
void gather(AlignedArray<T>& arr, const uint32_t* order, AlignedArray<Real>& tmp,
            const ThreadPool& pool) {
  static_assert(sizeof(T) == sizeof(Real));
  const std::size_t n = arr.size();
  if (n == 0) return;  // e.g. no boundary at all (every axis periodic): memcpy wants real pointers
  tmp.resize(n);
  T* dst = reinterpret_cast<T*>(tmp.data());
  const T* src = arr.data();
  pool.parallel_for(n, [&](std::size_t b, std::size_t e) {
    for (std::size_t i = b; i < e; ++i) dst[i] = src[order[i]];
  });
  std::memcpy(static_cast<void*>(arr.data()), dst, n * sizeof(T));
}
}  // namespace

template <int D>
void FluidParticles<D>::resize(std::size_t n) {
  for (int k = 0; k < D; ++k) { x[k].resize(n); v[k].resize(n); a[k].resize(n); }
  rho.resize(n);
  p.resize(n);
  id.resize(n);
}
template <int D>
void FluidParticles<D>::reserve(std::size_t n) {
  for (int k = 0; k < D; ++k) { x[k].reserve(n); v[k].reserve(n); a[k].reserve(n); }
  rho.reserve(n);
  p.reserve(n);
  id.reserve(n);
}
template <int D>
std::size_t FluidParticles<D>::bytes() const {
  std::size_t b = rho.bytes() + p.bytes() + id.bytes();
  for (int k = 0; k < D; ++k) b += x[k].bytes() + v[k].bytes() + a[k].bytes();
  return b;
}
template <int D>
std::size_t FluidParticles<D>::Spare::bytes() const {
  std::size_t b = id.bytes();
  for (const auto& a : xv) b += a.bytes();
  return b;
}

template <int D>
void FluidParticles<D>::permute_kinematics(const uint32_t* order, Spare& spare,
                                           const ThreadPool& pool) {
  const std::size_t n = size();
  Real* src[2 * D];
  Real* dst[2 * D];
  for (int k = 0; k < D; ++k) {
    src[k] = x[k].data();
    src[D + k] = v[k].data();
  }
  for (int k = 0; k < 2 * D; ++k) {
    spare.xv[k].resize(n);
    dst[k] = spare.xv[k].data();
  }
  spare.id.resize(n);
  pool.parallel_for(n, [&](std::size_t b, std::size_t e) {
    for (int k = 0; k < 2 * D; ++k)
      for (std::size_t i = b; i < e; ++i) dst[k][i] = src[k][order[i]];
    for (std::size_t i = b; i < e; ++i) spare.id[i] = id[order[i]];
  });
  for (int k = 0; k < D; ++k) {
    x[k].swap(spare.xv[k]);
    v[k].swap(spare.xv[D + k]);
  }
  id.swap(spare.id);
}

template <int D>
void BoundaryParticles<D>::resize(std::size_t n) {
  for (int k = 0; k < D; ++k) { x[k].resize(n); v[k].resize(n); local[k].resize(n); }
  psi.resize(n);
  owner.resize(n);
}
template <int D>
std::size_t BoundaryParticles<D>::bytes() const {
  std::size_t b = psi.bytes() + owner.bytes();
  for (int k = 0; k < D; ++k) b += x[k].bytes() + v[k].bytes() + local[k].bytes();
  return b;
}
template <int D>
void BoundaryParticles<D>::permute(const uint32_t* order, AlignedArray<Real>& tmp,
                                   const ThreadPool& pool) {
  for (int k = 0; k < D; ++k) {
    gather(x[k], order, tmp, pool);
    gather(v[k], order, tmp, pool);
    gather(local[k], order, tmp, pool);
  }
  gather(psi, order, tmp, pool);
  gather(owner, order, tmp, pool);
}

template struct FluidParticles<2>;
template struct FluidParticles<3>;
template struct BoundaryParticles<2>;
template struct BoundaryParticles<3>;

}  // namespace rtsph
