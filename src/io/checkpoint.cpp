#include "io/checkpoint.h"

#include <cerrno>
#include <cstring>
#include <fstream>
#include <iterator>
#include <string>
#include <string_view>
#include <vector>

#include <fmt/format.h>

#include "io/atomic_file.h"
#include "io/binary_out.h"

namespace rtsph::io {
namespace {

constexpr char kMagic[8] = {'R', 'T', 'S', 'P', 'H', 'C', 'K', '\0'};
constexpr std::uint32_t kMaxNameLength = 4096;

struct Header {
  std::uint32_t version, dimension;
  std::uint64_t fluid_count, boundary_count, scene_hash;
  std::uint32_t field_count;
};

struct FileField {
  std::string_view name, bytes;
};

/// Bounds-checked reading of the file image; running off the end means the file is truncated.
class Reader {
 public:
  Reader(std::string_view data, const std::filesystem::path& file) : data_(data), file_(file) {}

  template <class T>
  T get(const char* what) {
    T v;
    std::memcpy(&v, take(sizeof(T), what).data(), sizeof(T));
    return v;
  }
  std::string_view take(std::uint64_t n, const char* what) {
    if (n > data_.size() - pos_) throw error(fmt::format("truncated (file ends inside {})", what));
    auto s = data_.substr(pos_, n);
    pos_ += n;
    return s;
  }
  std::size_t pos() const { return pos_; }
  std::size_t remaining() const { return data_.size() - pos_; }
  CheckpointError error(const std::string& what) const {
    return CheckpointError(fmt::format("checkpoint '{}': {}", file_.string(), what));
  }

 private:
  std::string_view data_;
  std::size_t pos_ = 0;
  const std::filesystem::path& file_;
};

std::string read_whole_file(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    throw CheckpointError(fmt::format("checkpoint '{}': cannot open: {}", path.string(), std::strerror(errno)));
  }
  std::string data((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (in.bad()) throw CheckpointError(fmt::format("checkpoint '{}': read error", path.string()));
  return data;
}

/// Parses and checks everything that does not need the simulation: structure and checksum.
Header parse(Reader& r, std::string_view data, std::vector<FileField>& fields) {
  if (r.take(sizeof kMagic, "the magic number") != std::string_view(kMagic, sizeof kMagic)) {
    throw r.error("bad magic (not an rtsph checkpoint)");
  }
  Header h{};
  h.version = r.get<std::uint32_t>("the header");
  if (h.version != kCheckpointVersion) {
    throw r.error(fmt::format("unsupported version {} (this build reads version {})", h.version, kCheckpointVersion));
  }
  h.dimension = r.get<std::uint32_t>("the header");
  h.fluid_count = r.get<std::uint64_t>("the header");
  h.boundary_count = r.get<std::uint64_t>("the header");
  h.scene_hash = r.get<std::uint64_t>("the header");
  h.field_count = r.get<std::uint32_t>("the header");
  for (std::uint32_t i = 0; i < h.field_count; ++i) {
    auto len = r.get<std::uint32_t>("a field name");
    if (len == 0 || len > kMaxNameLength) throw r.error(fmt::format("field {} has a bad name length {}", i, len));
    FileField f;
    f.name = r.take(len, "a field name");
    f.bytes = r.take(r.get<std::uint64_t>("a field size"), "field data");
    fields.push_back(f);
  }
  const std::size_t body = r.pos();
  const auto stored = r.get<std::uint64_t>("the checksum");
  if (r.remaining() != 0) throw r.error(fmt::format("{} unexpected bytes after the checksum", r.remaining()));
  if (hash_bytes(data.substr(0, body)) != stored) throw r.error("checksum mismatch (the file is corrupt)");
  return h;
}

}  // namespace

void write_checkpoint(const std::filesystem::path& path, Simulation& sim, std::uint64_t scene_hash) {
  const auto fields = sim.state_fields();
  write_file_atomic(path, [&](std::ostream& os) {
    Fnv1a64 hash;
    auto put = [&](const void* p, std::size_t n) {
      if (n == 0) return;  // an empty field's data() may be null: no memcpy(nullptr, 0) below
      hash.update(p, n);
      os.write(static_cast<const char*>(p), static_cast<std::streamsize>(n));
    };
    auto put_u32 = [&](std::uint32_t v) { put(&v, sizeof v); };
    auto put_u64 = [&](std::uint64_t v) { put(&v, sizeof v); };
    put(kMagic, sizeof kMagic);
    put_u32(kCheckpointVersion);
    put_u32(static_cast<std::uint32_t>(sim.dimension()));
    put_u64(sim.fluid().count);
    put_u64(sim.boundary().count);
    put_u64(scene_hash);
    put_u32(static_cast<std::uint32_t>(fields.size()));
    for (const auto& f : fields) {
      put_u32(static_cast<std::uint32_t>(f.name.size()));
      put(f.name.data(), f.name.size());
      put_u64(f.bytes);
      put(f.data, f.bytes);
    }
    write_raw(os, hash.value());
  });
}

void read_checkpoint(const std::filesystem::path& path, Simulation& sim, std::uint64_t scene_hash) {
  const std::string data = read_whole_file(path);
  Reader r(data, path);
  std::vector<FileField> file_fields;
  const Header h = parse(r, data, file_fields);

  if (h.dimension != static_cast<std::uint32_t>(sim.dimension())) {
    throw r.error(fmt::format("dimension mismatch (file is {}D, the scene is {}D)", h.dimension, sim.dimension()));
  }
  if (h.scene_hash != scene_hash) {
    throw r.error(fmt::format("scene hash mismatch (file {:016x}, scene {:016x}): written for a different scene",
                              h.scene_hash, scene_hash));
  }
  if (h.boundary_count != sim.boundary().count) {
    throw r.error(fmt::format("boundary count mismatch (file {}, scene {})", h.boundary_count, sim.boundary().count));
  }
  // A valid checksum makes this unlikely, but a crafted count must not drive a huge allocation.
  if (h.fluid_count > data.size()) throw r.error(fmt::format("implausible fluid count {}", h.fluid_count));

  sim.prepare_state(h.fluid_count);
  const auto fields = sim.state_fields();
  if (fields.size() != file_fields.size()) {
    throw r.error(fmt::format("field count mismatch (file {}, solver {})", file_fields.size(), fields.size()));
  }
  for (std::size_t i = 0; i < fields.size(); ++i) {
    const auto& want = fields[i];
    const auto& got = file_fields[i];
    if (got.name != want.name || got.bytes.size() != want.bytes) {
      throw r.error(fmt::format("field {} is '{}' of {} bytes, the solver expects '{}' of {} bytes", i, got.name,
                                got.bytes.size(), want.name, want.bytes));
    }
  }
  for (std::size_t i = 0; i < fields.size(); ++i) {
    if (fields[i].bytes) std::memcpy(fields[i].data, file_fields[i].bytes.data(), fields[i].bytes);
  }
  sim.state_loaded();
}

}  // namespace rtsph::io
