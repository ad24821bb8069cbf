#pragma once
// Checkpoints: the complete solver state of one scene, to resume a run bit-for-bit. Layout
// (little-endian; docs/output-formats.md):
//   "RTSPHCK\0" | version u32 | dimension u32 | fluid count u64 | boundary count u64 |
//   scene hash u64 | field count u32 | per field: name length u32, name, byte count u64, bytes |
//   FNV-1a 64 of everything before it.
#include <cstdint>
#include <filesystem>

#include "io/errors.h"
#include "io/fnv.h"
#include "solvers/simulation.h"

namespace rtsph::io {

inline constexpr std::uint32_t kCheckpointVersion = 1;

/// Writes sim.state_fields() atomically (write_file_atomic); throws IoError. `scene_hash`
/// identifies the scene (hash_bytes of its canonical JSON) so a checkpoint is never loaded into
/// another scene.
void write_checkpoint(const std::filesystem::path& path, Simulation& sim, std::uint64_t scene_hash);

/// Validates the whole file, then sim.prepare_state(fluid count), fills sim.state_fields() and
/// calls sim.state_loaded(). Throws CheckpointError (one line: file and what is wrong) for any
/// unreadable, corrupt, truncated or mismatched file. Everything that can be checked without
/// the simulation is checked before it is touched; only a field list that disagrees with the
/// solver's (a different build) is found after prepare_state, leaving the state unspecified.
void read_checkpoint(const std::filesystem::path& path, Simulation& sim, std::uint64_t scene_hash);

}  // namespace rtsph::io
