#pragma once
// Writing rendered frames: PNG files (stb_image_write), MP4 through an ffmpeg pipe, or a
// numbered PNG sequence in a directory.
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

namespace rtsph::render {

/// Writes RGBA8 pixels (top row first) as PNG; false on failure.
bool write_png(const std::string& path, int width, int height, const unsigned char* rgba);

/// Full path of an executable found on PATH, or "" (e.g. find_on_path("ffmpeg")).
std::string find_on_path(const std::string& name);

/// True when every pixel equals the first one (an empty picture).
bool image_is_blank(const std::vector<unsigned char>& rgba);

/// A destination for a sequence of equally sized frames.
class FrameSink {
 public:
  virtual ~FrameSink() = default;
  /// RGBA8, top row first. Returns false (and sets error()) on failure.
  virtual bool write(const unsigned char* rgba) = 0;
  /// Flushes and closes; returns false if the encoder failed.
  virtual bool close() = 0;
  /// What is being written, e.g. "MP4 video out.mp4 (ffmpeg)" or "PNG frames in dir/".
  virtual std::string describe() const = 0;
  virtual std::string path() const = 0;
  const std::string& error() const { return error_; }

 protected:
  std::string error_;
};

/// Pipes frames into `ffmpeg` to make an H.264 MP4 (yuv420p; odd sizes are padded by one pixel).
std::unique_ptr<FrameSink> make_ffmpeg_sink(const std::string& ffmpeg, const std::string& path,
                                            int width, int height, double fps,
                                            std::string* error);
/// Writes dir/<prefix>000000.png, dir/<prefix>000001.png, … (creates the directory).
std::unique_ptr<FrameSink> make_png_sequence_sink(const std::string& dir, int width, int height,
                                                  const std::string& prefix, std::string* error);

}  // namespace rtsph::render
