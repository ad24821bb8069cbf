#pragma once
// Crash-safe file replacement: readers see either the old file or the complete new one, never
// a partial write, even if the process dies or the machine loses power mid-write.
#include <filesystem>
#include <functional>
#include <ostream>
#include <string_view>

#include "io/errors.h"

namespace rtsph::io {

/// Writes `body`'s output to a hidden temporary file next to `path` (".NAME.tmp.PID"), fsyncs
/// it, renames it over `path` and fsyncs the directory. On any failure the temporary file is
/// removed, `path` keeps its previous content and IoError names the path and the OS error. An
/// exception thrown by `body` propagates unchanged after the same clean-up.
void write_file_atomic(const std::filesystem::path& path,
                       const std::function<void(std::ostream&)>& body);

/// The same for content already in memory.
void write_file_atomic(const std::filesystem::path& path, std::string_view bytes);

/// The same for a library that writes only to a path it opens itself (OpenVDB's io::File):
/// `body` writes the temporary file named by its argument, which is then fsynced and renamed
/// over `path` as above.
void write_file_atomic_via_path(const std::filesystem::path& path,
                                const std::function<void(const std::filesystem::path&)>& body);

/// Creates `dir` and its parents if missing; throws IoError if that fails or `dir` exists but
/// is not a directory.
void ensure_directory(const std::filesystem::path& dir);

/// Throws IoError unless `path` could be written by write_file_atomic: its directory exists and
/// `path` is not a directory. For outputs written at the end of a long run (a summary, a
/// benchmark table), checked before it starts.
void check_file_target(const std::filesystem::path& path);

}  // namespace rtsph::io
