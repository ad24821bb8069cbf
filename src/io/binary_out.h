#pragma once
// Raw little-endian output for the binary formats. Values are written in host order, which the
// assertion pins to little-endian (every platform rtsph targets).
#include <bit>
#include <cstdint>
#include <ostream>
#include <vector>

namespace rtsph::io {

static_assert(std::endian::native == std::endian::little, "binary writers assume a little-endian host");

template <class T>
void write_raw(std::ostream& os, const T& value) {
  os.write(reinterpret_cast<const char*>(&value), sizeof(T));
}

template <class T>
void write_raw(std::ostream& os, const std::vector<T>& values) {
  os.write(reinterpret_cast<const char*>(values.data()), static_cast<std::streamsize>(values.size() * sizeof(T)));
}

}  // namespace rtsph::io
