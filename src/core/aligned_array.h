#pragma once
// Cache-line aligned storage with a tail of kPad spare elements, so 8-wide loads that start
// inside a range may read past its last element without touching unowned memory.
#include <algorithm>
#include <cstddef>
#include <cstdlib>
#include <cstring>
#include <new>
#include <sys/mman.h>
#include <utility>

namespace rtsph {

template <class T>
class AlignedArray {
 public:
  static constexpr std::size_t kPad = 16;
  AlignedArray() = default;
  explicit AlignedArray(std::size_t n) { resize(n); }
  AlignedArray(const AlignedArray& o) { *this = o; }
  AlignedArray(AlignedArray&& o) noexcept { swap(o); }
  AlignedArray& operator=(const AlignedArray& o) {
    if (this != &o) {
      resize(o.size_);
      if (o.size_) std::memcpy(data_, o.data_, o.size_ * sizeof(T));
    }
    return *this;
  }
  AlignedArray& operator=(AlignedArray&& o) noexcept { swap(o); return *this; }
  ~AlignedArray() { std::free(data_); }

  void swap(AlignedArray& o) noexcept {
    std::swap(data_, o.data_);
    std::swap(size_, o.size_);
    std::swap(cap_, o.cap_);
  }
  /// Grows capacity geometrically. Every element past size() is zero, the pad included: new
  /// elements start at zero, and shrinking zeroes what it drops. 8-wide loads read the elements
  /// past a range's end as masked lanes, and sums weight those lanes by zero, which leaves zero
  /// only if they are finite. (Scratch that had carried int data, -1 being a NaN's bits, swapped
  /// in as a shorter array turned WCSPH's wall pressure into NaN at its first step: 3D, particle
  /// shifting, more boundary samples than fluid particles; session 38.)
  void resize(std::size_t n) {
    if (n > cap_) reserve(std::max(n, cap_ + cap_ / 2));
    if (n > size_)
      std::memset(static_cast<void*>(data_ + size_), 0, (n - size_) * sizeof(T));
    else if (n < size_)
      std::memset(static_cast<void*>(data_ + n), 0, (size_ - n) * sizeof(T));
    size_ = n;
  }
  void reserve(std::size_t cap) {
    if (cap <= cap_) return;
    std::size_t bytes = ((cap + kPad) * sizeof(T) + 63) / 64 * 64;
    const bool huge = bytes >= kHugeFrom;
    if (huge) bytes = (bytes + kHuge - 1) / kHuge * kHuge;
    T* p = static_cast<T*>(std::aligned_alloc(huge ? kHuge : 64, bytes));
    if (!p) throw std::bad_alloc();
    if (huge) madvise(p, bytes, MADV_HUGEPAGE);
    std::memset(static_cast<void*>(p), 0, bytes);
    if (size_) std::memcpy(static_cast<void*>(p), data_, size_ * sizeof(T));
    std::free(data_);
    data_ = p;
    cap_ = cap;
  }
  std::size_t size() const { return size_; }
  std::size_t capacity() const { return cap_; }
  std::size_t bytes() const { return data_ ? (cap_ + kPad) * sizeof(T) : 0; }
  T* data() { return data_; }
  const T* data() const { return data_; }
  T& operator[](std::size_t i) { return data_[i]; }
  const T& operator[](std::size_t i) const { return data_[i]; }
  T* begin() { return data_; }
  T* end() { return data_ + size_; }
  const T* begin() const { return data_; }
  const T* end() const { return data_ + size_; }

 private:
  // Arrays of 4 MiB and more (neighbour lists, per-pair caches) ask for 2 MiB pages: streamed
  // with 4 KiB pages, DFSPH's sweeps at 60k particles missed the TLB every few particles
  // (single thread: the residual sweep 6.9 → 5.3 ms, the pressure sweep 4.0 → 3.0 ms).
  static constexpr std::size_t kHuge = std::size_t(2) << 20, kHugeFrom = std::size_t(4) << 20;
  T* data_ = nullptr;
  std::size_t size_ = 0, cap_ = 0;
};

}  // namespace rtsph
