#pragma once
// Checkpoints as `rtsph run` uses them: the binary state (io/checkpoint) plus the scene it
// belongs to, stored next to it as `<stem>.scene-<hash>.json` so `--resume FILE` needs no
// scene argument. The scene file's name carries the scene hash of the checkpoint header, so a
// checkpoint always finds its own scene even if a crash hit between the two writes.
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "solvers/simulation.h"

namespace rtsph::app {

namespace fs = std::filesystem;

/// hash_bytes(scene_to_json(spec)): the scene hash stored in checkpoint headers.
std::uint64_t scene_hash(const SimSpec& spec);

/// The header fields of a checkpoint file, after checking magic, version, size and checksum
/// (the field list is checked when the state is loaded). Throws io::CheckpointError.
struct CheckpointInfo {
  std::uint32_t version = 0, dimension = 0;
  std::uint64_t fluid_count = 0, boundary_count = 0, scene_hash = 0;
};
CheckpointInfo inspect_checkpoint(const fs::path& file);

/// `<dir>/<stem>.scene-<16 hex>.json` for checkpoint `<dir>/<stem>.ckpt`.
fs::path scene_file_for(const fs::path& checkpoint, std::uint64_t hash);

/// Writes the scene file (from sim.spec(), which includes live changes such as a halved dt)
/// and then the checkpoint, both atomically; removes scene files of older scenes for the same
/// stem. Throws io::IoError.
void save_checkpoint(const fs::path& file, Simulation& sim);

/// The scene stored with a checkpoint (parsed and validated). Throws io::CheckpointError if the
/// scene file is missing or does not hash to the checkpoint's scene hash.
SimSpec load_checkpoint_scene(const fs::path& checkpoint);

/// `--resume` accepts a checkpoint file or a directory; for a directory, the checkpoint named
/// ckpt_<step>.ckpt with the highest step. Throws io::CheckpointError if there is none.
fs::path resolve_resume_path(const fs::path& file_or_dir);

/// "ckpt_000001234.ckpt": periodic and final checkpoints in a checkpoint directory.
std::string checkpoint_file_name(std::uint64_t step);

/// Letters, digits, '-' and '_' of a scene name (others become '_'), for file names.
std::string safe_file_stem(const std::string& name);

/// Saves the state to the first of `dirs` where that works (used when the planned location
/// failed: full disk, read-only directory). Returns the file written, or an empty path with
/// `errors` listing why each place failed.
fs::path save_checkpoint_somewhere(Simulation& sim, const std::vector<fs::path>& dirs,
                                   const std::string& file_name, std::string& errors);

/// The usual fallback places for save_checkpoint_somewhere: $TMPDIR (or /tmp), then the
/// current directory, skipping `except`.
std::vector<fs::path> fallback_dirs(const fs::path& except);

}  // namespace rtsph::app
