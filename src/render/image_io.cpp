#include "render/image_io.h"

#include <sys/stat.h>
#include <unistd.h>

#include <csignal>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <string_view>

#include <fmt/format.h>
#include <stb/stb_image_write.h>

namespace rtsph::render {

bool write_png(const std::string& path, int width, int height, const unsigned char* rgba) {
  return stbi_write_png(path.c_str(), width, height, 4, rgba, width * 4) != 0;
}

std::string find_on_path(const std::string& name) {
  const char* path = std::getenv("PATH");
  if (!path) return "";
  std::string_view p(path);
  while (!p.empty()) {
    auto colon = p.find(':');
    std::string dir = colon == 0 ? std::string(".") : std::string(p.substr(0, colon));
    std::string full = dir + "/" + name;
    struct stat st {};
    if (::stat(full.c_str(), &st) == 0 && S_ISREG(st.st_mode) && ::access(full.c_str(), X_OK) == 0)
      return full;
    if (colon == std::string_view::npos) break;
    p.remove_prefix(colon + 1);
  }
  return "";
}

bool image_is_blank(const std::vector<unsigned char>& rgba) {
  if (rgba.size() < 4) return true;
  for (std::size_t i = 4; i < rgba.size(); i += 4)
    if (std::memcmp(rgba.data(), rgba.data() + i, 4) != 0) return false;
  return true;
}

namespace {

std::string shell_quote(const std::string& s) {
  std::string r = "'";
  for (char c : s) r += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return r + "'";
}

class FfmpegSink : public FrameSink {
 public:
  FfmpegSink(FILE* pipe, std::string path, int w, int h)
      : pipe_(pipe), path_(std::move(path)), w_(w), h_(h) {}
  ~FfmpegSink() override { close(); }
  bool write(const unsigned char* rgba) override {
    if (!pipe_) return false;
    const std::size_t bytes = static_cast<std::size_t>(w_) * h_ * 4;
    if (std::fwrite(rgba, 1, bytes, pipe_) != bytes) {
      error_ = "ffmpeg stopped reading frames";
      return false;
    }
    ++frames_;
    return true;
  }
  bool close() override {
    if (!pipe_) return closed_ok_;
    int rc = pclose(pipe_);
    pipe_ = nullptr;
    closed_ok_ = rc == 0;
    if (!closed_ok_) error_ = fmt::format("ffmpeg exited with status {}", rc);
    return closed_ok_;
  }
  std::string describe() const override { return fmt::format("MP4 video {} (ffmpeg)", path_); }
  std::string path() const override { return path_; }

 private:
  FILE* pipe_;
  std::string path_;
  int w_, h_;
  long frames_ = 0;
  bool closed_ok_ = false;
};

class PngSequenceSink : public FrameSink {
 public:
  PngSequenceSink(std::string dir, std::string prefix, int w, int h)
      : dir_(std::move(dir)), prefix_(std::move(prefix)), w_(w), h_(h) {}
  bool write(const unsigned char* rgba) override {
    std::string file = fmt::format("{}/{}{:06d}.png", dir_, prefix_, index_);
    if (!write_png(file, w_, h_, rgba)) {
      error_ = fmt::format("cannot write {}", file);
      return false;
    }
    ++index_;
    return true;
  }
  bool close() override { return true; }
  std::string describe() const override {
    return fmt::format("PNG frames {}/{}000000.png … ({} written)", dir_, prefix_, index_);
  }
  std::string path() const override { return dir_; }

 private:
  std::string dir_, prefix_;
  int w_, h_;
  int index_ = 0;
};

}  // namespace

std::unique_ptr<FrameSink> make_ffmpeg_sink(const std::string& ffmpeg, const std::string& path,
                                            int width, int height, double fps,
                                            std::string* error) {
  // Writing into a closed pipe must not kill the process: report it instead.
  std::signal(SIGPIPE, SIG_IGN);
  std::string cmd = fmt::format(
      "{} -hide_banner -loglevel error -y -f rawvideo -pix_fmt rgba -s {}x{} -r {} -i - "
      "-vf 'pad=ceil(iw/2)*2:ceil(ih/2)*2' -c:v libx264 -preset veryfast -crf 20 -pix_fmt yuv420p "
      "-movflags +faststart {}",
      shell_quote(ffmpeg), width, height, fps, shell_quote(path));
  FILE* pipe = popen(cmd.c_str(), "w");
  if (!pipe) {
    if (error) *error = fmt::format("cannot start {}", ffmpeg);
    return nullptr;
  }
  return std::make_unique<FfmpegSink>(pipe, path, width, height);
}

std::unique_ptr<FrameSink> make_png_sequence_sink(const std::string& dir, int width, int height,
                                                  const std::string& prefix, std::string* error) {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec || !std::filesystem::is_directory(dir)) {
    if (error) *error = fmt::format("cannot create directory {}: {}", dir, ec.message());
    return nullptr;
  }
  return std::make_unique<PngSequenceSink>(dir, prefix, width, height);
}

}  // namespace rtsph::render
