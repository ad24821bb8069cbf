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
// An unaligned vector type: its stores alias floats only (memcpy's alias everything, which made
// GCC reload every array pointer of a loop after each store).
typedef float f8u __attribute__((vector_size(32), aligned(4)));
inline void store(float* p, f8 v) { *reinterpret_cast<f8u*>(p) = v; }
inline f8 splat(float s) { return f8{} + s; }
/// Lanes of a field: eight consecutive elements from j (grid ranges), or the elements at the
/// eight indices j (neighbour lists). Pair-loop bodies read fields through at() and so work
/// with either walk.
inline f8 at(const float* p, unsigned j) { return load(p + j); }
inline f8 at(const float* p, i8 j) {
#if defined(__AVX2__)
  return _mm256_i32gather_ps(p, reinterpret_cast<__m256i>(j), 4);
#else
  f8 v;
  for (int i = 0; i < kWidth; ++i) v[i] = p[j[i]];
  return v;
#endif
}
inline i8 lane_index() { return i8{0, 1, 2, 3, 4, 5, 6, 7}; }
/// The four fields of eight 16-byte records (e.g. x, y, z, w) at the indices j, as four
/// batches: eight 16-byte loads and a transpose instead of four gathers (a gather costs about as
/// much as its eight loads; DFSPH's residual sweep at 60k: three gathers were half its time).
inline void at_packed4(const float* rec, i8 j, f8& a, f8& b, f8& c, f8& w) {
#if defined(__AVX__)
  const __m128 r0 = _mm_load_ps(rec + 4 * j[0]), r1 = _mm_load_ps(rec + 4 * j[1]);
  const __m128 r2 = _mm_load_ps(rec + 4 * j[2]), r3 = _mm_load_ps(rec + 4 * j[3]);
  const __m256 q0 = _mm256_insertf128_ps(_mm256_castps128_ps256(r0), _mm_load_ps(rec + 4 * j[4]), 1);
  const __m256 q1 = _mm256_insertf128_ps(_mm256_castps128_ps256(r1), _mm_load_ps(rec + 4 * j[5]), 1);
  const __m256 q2 = _mm256_insertf128_ps(_mm256_castps128_ps256(r2), _mm_load_ps(rec + 4 * j[6]), 1);
  const __m256 q3 = _mm256_insertf128_ps(_mm256_castps128_ps256(r3), _mm_load_ps(rec + 4 * j[7]), 1);
  // Lanes (0,4) (1,5) (2,6) (3,7) pairwise: unpack, then pick each field.
  const __m256 t0 = _mm256_unpacklo_ps(q0, q1), t1 = _mm256_unpackhi_ps(q0, q1);
  const __m256 t2 = _mm256_unpacklo_ps(q2, q3), t3 = _mm256_unpackhi_ps(q2, q3);
  a = _mm256_shuffle_ps(t0, t2, 0x44);
  b = _mm256_shuffle_ps(t0, t2, 0xEE);
  c = _mm256_shuffle_ps(t1, t3, 0x44);
  w = _mm256_shuffle_ps(t1, t3, 0xEE);
#else
  for (int i = 0; i < kWidth; ++i) {
    a[i] = rec[4 * j[i]];
    b[i] = rec[4 * j[i] + 1];
    c[i] = rec[4 * j[i] + 2];
    w[i] = rec[4 * j[i] + 3];
  }
#endif
}
/// The two fields of eight 8-byte records (2D: vx, vy) at the indices j: eight 8-byte loads
/// and two shuffles instead of two gathers.
inline void at_packed2(const float* rec, i8 j, f8& a, f8& b) {
#if defined(__AVX__)
  // Each record read as one 8-byte value through memcpy: a load through a double* would alias
  // the floats it reads, and GCC then moved it before their stores (seen at -O3).
  auto record = [&](int l) {
    double r;
    std::memcpy(&r, rec + 2 * j[l], sizeof r);
    return r;
  };
  auto pair = [&](int l0, int l1) {  // records l0 and l1 as (a, b, a, b)
    return _mm_castpd_ps(_mm_set_pd(record(l1), record(l0)));
  };
  const __m256 q0 = _mm256_insertf128_ps(_mm256_castps128_ps256(pair(0, 1)), pair(4, 5), 1);
  const __m256 q1 = _mm256_insertf128_ps(_mm256_castps128_ps256(pair(2, 3)), pair(6, 7), 1);
  a = _mm256_shuffle_ps(q0, q1, 0x88);  // (q0[0], q0[2], q1[0], q1[2]) per 128-bit half
  b = _mm256_shuffle_ps(q0, q1, 0xDD);
#else
  for (int i = 0; i < kWidth; ++i) {
    a[i] = rec[2 * j[i]];
    b[i] = rec[2 * j[i] + 1];
  }
#endif
}
/// The first three fields (the fourth is left unread by the optimiser).
inline void at_packed3(const float* rec, i8 j, f8& a, f8& b, f8& c) {
  f8 w;
  at_packed4(rec, j, a, b, c, w);
}

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
inline f8 max0(f8 x) {
#if defined(__AVX__)
  return reinterpret_cast<f8>(_mm256_max_ps(reinterpret_cast<__m256>(x), _mm256_setzero_ps()));
#else
  return x > 0.0f ? x : f8{};
#endif
}
inline f8 select(i8 m, f8 a, f8 b) { return m ? a : b; }
inline bool any(i8 m) {
#if defined(__AVX__)
  return _mm256_movemask_ps(reinterpret_cast<__m256>(m)) != 0;
#else
  for (int i = 0; i < kWidth; ++i) if (m[i]) return true;
  return false;
#endif
}
/// Bit l set when lane l of the mask is.
inline unsigned bits(i8 m) {
#if defined(__AVX__)
  return unsigned(_mm256_movemask_ps(reinterpret_cast<__m256>(m)));
#else
  unsigned b = 0;
  for (int i = 0; i < kWidth; ++i) b |= (m[i] ? 1u : 0u) << i;
  return b;
#endif
}
/// Writes base + l for each lane l set in `bits`, in lane order, to out[0..popcount): eight
/// slots are written (the ones past the count hold junk), so out needs eight of room.
inline void store_packed(unsigned* out, unsigned base, unsigned bits) {
#if defined(__AVX2__)
  // Lane indices of each 8-bit mask, packed 4 bits each: built once, 256 entries.
  static const auto table = [] {
    struct T { unsigned long long v[256]; } t{};
    for (unsigned m = 0; m < 256; ++m) {
      unsigned long long packed = 0;
      int k = 0;
      for (unsigned l = 0; l < 8; ++l)
        if (m & (1u << l)) packed |= (unsigned long long)l << (8 * k++);
      t.v[m] = packed;
    }
    return t;
  }();
  const __m256i lanes = _mm256_cvtepu8_epi32(_mm_cvtsi64_si128((long long)table.v[bits & 255u]));
  const __m256i v = _mm256_add_epi32(lanes, _mm256_set1_epi32(int(base)));
  _mm256_storeu_si256(reinterpret_cast<__m256i*>(out), v);
#else
  int k = 0;
  for (unsigned l = 0; l < 8; ++l)
    if (bits & (1u << l)) out[k++] = base + l;
#endif
}
/// Sum of the lanes as a fixed tree, ((0+4)+(2+6)) + ((1+5)+(3+7)), so it is the same on every
/// run and thread count. A tree is three vector adds; a lane-by-lane sum is seven dependent
/// scalar adds plus seven extracts, and a pair loop's epilogue sums up to nine batches per
/// particle (PBF's λ pass: ~11% of its time went there).
inline float hsum(f8 v) {
#if defined(__AVX__)
  const __m256 x = reinterpret_cast<__m256>(v);
  __m128 s = _mm_add_ps(_mm256_castps256_ps128(x), _mm256_extractf128_ps(x, 1));  // 0+4 … 3+7
  s = _mm_add_ps(s, _mm_movehl_ps(s, s));                                  // (0+4)+(2+6), (1+5)+(3+7)
  s = _mm_add_ss(s, _mm_movehdup_ps(s));
  return _mm_cvtss_f32(s);
#else
  const float a = (v[0] + v[4]) + (v[2] + v[6]), b = (v[1] + v[5]) + (v[3] + v[7]);
  return a + b;
#endif
}

// Scalar twins so kernels can be written once for float and f8.
inline float sqrt(float x) { return std::sqrt(x); }
inline float rsqrt(float x) { return 1.0f / std::sqrt(x); }
inline float rcp(float x) { return 1.0f / x; }
inline float exp(float x) { return std::exp(x); }
inline float max0(float x) { return x > 0.0f ? x : 0.0f; }

}  // namespace rtsph::simd
