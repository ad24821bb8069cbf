#include "apps/run_checkpoint.h"

#include <fmt/format.h>

#include <algorithm>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iterator>
#include <system_error>

#include "io/atomic_file.h"
#include "io/checkpoint.h"
#include "io/errors.h"
#include "io/fnv.h"
#include "scene/scene.h"

namespace rtsph::app {
namespace {

constexpr char kMagic[8] = {'R', 'T', 'S', 'P', 'H', 'C', 'K', '\0'};
constexpr std::size_t kHeaderBytes = 8 + 4 + 4 + 8 + 8 + 8 + 4;  // up to the field count
constexpr std::size_t kChecksumBytes = 8;

io::CheckpointError error(const fs::path& file, const std::string& what) {
  return io::CheckpointError(fmt::format("checkpoint '{}': {}", file.string(), what));
}

std::string read_file(const fs::path& file, bool checkpoint) {
  std::ifstream in(file, std::ios::binary);
  if (!in) {
    const std::string why = std::strerror(errno);
    if (checkpoint) throw error(file, "cannot open: " + why);
    throw io::IoError(fmt::format("cannot read '{}': {}", file.string(), why));
  }
  std::string data((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (in.bad()) throw error(file, "read error");
  return data;
}

template <class T>
T get(const std::string& data, std::size_t at) {
  T v;
  std::memcpy(&v, data.data() + at, sizeof v);
  return v;
}

/// Parses the step out of "ckpt_<digits>.ckpt"; -1 for other names.
long long step_of(const fs::path& p) {
  const std::string n = p.filename().string();
  if (n.size() <= 10 || n.rfind("ckpt_", 0) != 0 || p.extension() != ".ckpt") return -1;
  const std::string digits = n.substr(5, n.size() - 10);
  if (digits.empty() || digits.size() > 18) return -1;
  for (char c : digits)
    if (c < '0' || c > '9') return -1;
  return std::stoll(digits);
}

}  // namespace

std::uint64_t scene_hash(const SimSpec& spec) { return io::hash_bytes(scene_to_json(spec)); }

CheckpointInfo inspect_checkpoint(const fs::path& file) {
  std::error_code ec;
  if (fs::is_directory(file, ec)) throw error(file, "is a directory");
  const std::string data = read_file(file, true);
  if (std::memcmp(data.data(), kMagic, std::min(data.size(), sizeof kMagic)) != 0) {
    throw error(file, "bad magic (not an rtsph checkpoint)");
  }
  if (data.size() < kHeaderBytes + kChecksumBytes) {
    throw error(file, fmt::format("truncated ({} bytes, shorter than the header)", data.size()));
  }
  CheckpointInfo info;
  info.version = get<std::uint32_t>(data, 8);
  if (info.version != io::kCheckpointVersion) {
    throw error(file, fmt::format("unsupported version {} (this build reads version {})", info.version,
                                  io::kCheckpointVersion));
  }
  info.dimension = get<std::uint32_t>(data, 12);
  info.fluid_count = get<std::uint64_t>(data, 16);
  info.boundary_count = get<std::uint64_t>(data, 24);
  info.scene_hash = get<std::uint64_t>(data, 32);
  // Walk the field list so that a short file is reported as truncated, not as corrupt.
  std::size_t at = kHeaderBytes;
  const auto fields = get<std::uint32_t>(data, kHeaderBytes - 4);
  for (std::uint32_t i = 0; i < fields; ++i) {
    if (data.size() - at < 4) throw error(file, fmt::format("truncated (file ends inside field {})", i));
    const std::uint64_t name = get<std::uint32_t>(data, at);
    if (data.size() - at - 4 < name + 8) throw error(file, fmt::format("truncated (file ends inside field {})", i));
    const std::uint64_t bytes = get<std::uint64_t>(data, at + 4 + name);
    at += 4 + name + 8;
    if (data.size() - at < bytes) throw error(file, fmt::format("truncated (file ends inside field {})", i));
    at += bytes;
  }
  if (data.size() - at < kChecksumBytes) throw error(file, "truncated (file ends before the checksum)");
  const std::size_t body = data.size() - kChecksumBytes;
  if (io::hash_bytes(std::string_view(data).substr(0, body)) != get<std::uint64_t>(data, body)) {
    throw error(file, "checksum mismatch (the file is corrupt)");
  }
  if (info.dimension != 2 && info.dimension != 3) {
    throw error(file, fmt::format("bad dimension {}", info.dimension));
  }
  return info;
}

fs::path scene_file_for(const fs::path& checkpoint, std::uint64_t hash) {
  return checkpoint.parent_path() / fmt::format("{}.scene-{:016x}.json", checkpoint.stem().string(), hash);
}

void save_checkpoint(const fs::path& file, Simulation& sim) {
  const std::string json = scene_to_json(sim.spec());
  const std::uint64_t hash = io::hash_bytes(json);
  const fs::path scene = scene_file_for(file, hash);
  std::error_code ec;
  if (!fs::exists(scene, ec)) io::write_file_atomic(scene, json + "\n");
  io::write_checkpoint(file, sim, hash);
  // Scene files of the same stem with another hash belong to checkpoints this one replaced.
  const std::string prefix = file.stem().string() + ".scene-";
  const fs::path dir = file.parent_path().empty() ? fs::path(".") : file.parent_path();
  for (const auto& e : fs::directory_iterator(dir, ec)) {
    const std::string n = e.path().filename().string();
    if (n.rfind(prefix, 0) == 0 && n.size() == prefix.size() + 16 + 5 && e.path().extension() == ".json" &&
        e.path().filename() != scene.filename()) {
      fs::remove(e.path(), ec);
    }
  }
}

SimSpec load_checkpoint_scene(const fs::path& checkpoint) {
  const CheckpointInfo info = inspect_checkpoint(checkpoint);
  const fs::path scene = scene_file_for(checkpoint, info.scene_hash);
  std::error_code ec;
  if (!fs::exists(scene, ec)) {
    throw error(checkpoint, fmt::format("its scene file '{}' is missing; name the scene: rtsph run SCENE --resume {}",
                                        scene.string(), checkpoint.string()));
  }
  const std::string text = read_file(scene, false);
  std::string json = text;
  if (!json.empty() && json.back() == '\n') json.pop_back();
  if (io::hash_bytes(json) != info.scene_hash) {
    throw error(checkpoint, fmt::format("scene file '{}' was modified (its hash is not the checkpoint's)",
                                        scene.string()));
  }
  SimSpec spec = parse_scene(text, scene.string());
  if (scene_hash(spec) != info.scene_hash) {
    throw error(checkpoint, fmt::format("scene file '{}' does not read back to the same scene", scene.string()));
  }
  return spec;
}

fs::path resolve_resume_path(const fs::path& file_or_dir) {
  std::error_code ec;
  if (!fs::is_directory(file_or_dir, ec)) return file_or_dir;
  fs::path best;
  long long best_step = -1;
  for (const auto& e : fs::directory_iterator(file_or_dir, ec)) {
    const long long s = step_of(e.path());
    if (s > best_step) { best_step = s; best = e.path(); }
  }
  if (best.empty()) throw error(file_or_dir, "directory holds no ckpt_<step>.ckpt file");
  return best;
}

std::string checkpoint_file_name(std::uint64_t step) { return fmt::format("ckpt_{:09d}.ckpt", step); }

std::string safe_file_stem(const std::string& name) {
  std::string s = name.empty() ? "scene" : name;
  for (char& c : s) {
    const bool ok = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '-' || c == '_';
    if (!ok) c = '_';
  }
  return s.substr(0, 100);
}

fs::path save_checkpoint_somewhere(Simulation& sim, const std::vector<fs::path>& dirs,
                                   const std::string& file_name, std::string& errors) {
  for (const auto& d : dirs) {
    const fs::path file = d / file_name;
    try {
      io::ensure_directory(d);
      save_checkpoint(file, sim);
      return file;
    } catch (const std::exception& e) {
      errors += fmt::format("{}{}", errors.empty() ? "" : "; ", e.what());
    }
  }
  return {};
}

std::vector<fs::path> fallback_dirs(const fs::path& except) {
  std::vector<fs::path> dirs;
  const char* tmp = std::getenv("TMPDIR");
  dirs.emplace_back(tmp && *tmp ? tmp : "/tmp");
  std::error_code ec;
  const fs::path cwd = fs::current_path(ec);
  if (!ec) dirs.push_back(cwd);
  std::vector<fs::path> out;
  const fs::path ex = fs::weakly_canonical(except.empty() ? fs::path("/nonexistent") : except, ec);
  for (const auto& d : dirs) {
    const fs::path c = fs::weakly_canonical(d, ec);
    if (!except.empty() && c == ex) continue;
    bool dup = false;
    for (const auto& o : out) dup |= fs::weakly_canonical(o, ec) == c;
    if (!dup) out.push_back(d);
  }
  return out;
}

}  // namespace rtsph::app
