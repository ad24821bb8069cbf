#pragma once
// FNV-1a 64: tiny, dependency-free and good enough to detect corruption and to fingerprint a
// scene; not a cryptographic hash.
#include <cstddef>
#include <cstdint>
#include <string_view>

namespace rtsph::io {

/// Incremental form, so a checkpoint can be hashed while it streams to disk.
class Fnv1a64 {
 public:
  void update(const void* data, std::size_t n) {
    const auto* p = static_cast<const unsigned char*>(data);
    for (std::size_t i = 0; i < n; ++i) h_ = (h_ ^ p[i]) * 0x100000001b3ULL;
  }
  std::uint64_t value() const { return h_; }

 private:
  std::uint64_t h_ = 0xcbf29ce484222325ULL;
};

inline std::uint64_t hash_bytes(std::string_view bytes) {
  Fnv1a64 h;
  h.update(bytes.data(), bytes.size());
  return h.value();
}

}  // namespace rtsph::io
