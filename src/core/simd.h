#pragma once
// Eight-lane float batch on GCC/Clang vector extensions: the pair loops run over contiguous
// particle ranges (cells are sorted), so loading 8 candidates at once is a plain unaligned load.
#include <cmath>
#include <cstring>
#if defined(__AVX__)
#include <immintrin.h>
#endif

namespace rtsph::simd {

constexpr int kWidth = 8;
typedef float f8 __attribute__((vector_size(32)));
typedef int i8 __attribute__((vector_size(32)));

inline f8 load(const float* p) { f8 v; std::memcpy(&v, p, sizeof v); return v; }
inline f8 splat(float s) { return f8{} + s; }
inline i8 lane_index() { return i8{0, 1, 2, 3, 4, 5, 6, 7}; }

inline f8 sqrt(f8 x) {
#if defined(__AVX__)
  return _mm256_sqrt_ps(x);
#else
  for (int i = 0; i < kWidth; ++i) x[i] = std::sqrt(x[i]);
  return x;
#endif
}
/// 1/√x to ~23 bits: the 12-bit hardware estimate plus one Newton step, several times cheaper
/// than a square root and a division. Callers keep x > 0.
inline f8 rsqrt(f8 x) {
#if defined(__AVX__)
  const f8 y = _mm256_rsqrt_ps(x);
  return y * (1.5f - 0.5f * x * y * y);
#else
  for (int i = 0; i < kWidth; ++i) x[i] = 1.0f / std::sqrt(x[i]);
  return x;
#endif
}
/// 1/x to ~23 bits (estimate plus one Newton step). Callers keep x away from 0.
inline f8 rcp(f8 x) {
#if defined(__AVX__)
  const f8 y = _mm256_rcp_ps(x);
  return y * (2.0f - x * y);
#else
  return 1.0f / x;
#endif
}
inline f8 exp(f8 x) {
  for (int i = 0; i < kWidth; ++i) x[i] = std::exp(x[i]);
  return x;
}
inline f8 max0(f8 x) { return x > 0.0f ? x : f8{}; }
inline f8 select(i8 m, f8 a, f8 b) { return m ? a : b; }
inline bool any(i8 m) {
#if defined(__AVX__)
  return _mm256_movemask_ps(reinterpret_cast<__m256>(m)) != 0;
#else
  for (int i = 0; i < kWidth; ++i) if (m[i]) return true;
  return false;
#endif
}
/// Lane order is fixed, so the sum is the same on every run and thread count.
inline float hsum(f8 v) {
  float s = 0.0f;
  for (int i = 0; i < kWidth; ++i) s += v[i];
  return s;
}

// Scalar twins so kernels can be written once for float and f8.
inline float sqrt(float x) { return std::sqrt(x); }
inline float rsqrt(float x) { return 1.0f / std::sqrt(x); }
inline float rcp(float x) { return 1.0f / x; }
inline float exp(float x) { return std::exp(x); }
inline float max0(float x) { return x > 0.0f ? x : 0.0f; }

}  // namespace rtsph::simd
