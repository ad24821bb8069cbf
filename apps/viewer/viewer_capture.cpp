// The viewer's screenshots (F12, the script's `screenshot`) and recording (V: MP4 through ffmpeg,
// else PNG frames), read back from the window after each frame (the Viewer class: viewer.h).
#include <epoxy/gl.h>
// epoxy provides GL; GLFW must not include a GL header of its own.
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <fmt/format.h>

#include <string>

#include "apps/viewer/viewer.h"
#include "render/image_io.h"

namespace rtsph::app {

void Viewer::toggle_recording() {
  if (video_) {
    const bool ok = video_->close();
    status(ok ? fmt::format("recording stopped: {}", video_->describe())
              : fmt::format("recording failed: {}", video_->error()),
           !ok);
    video_.reset();
    return;
  }
  int w = 1, h = 1;
  glfwGetFramebufferSize(win_, &w, &h);
  const std::string base = fmt::format("rtsph_{}_{}", spec_.name, timestamp());
  std::string err;
  const std::string ffmpeg = render::find_on_path("ffmpeg");
  if (!ffmpeg.empty())
    video_ = render::make_ffmpeg_sink(ffmpeg, base + ".mp4", w, h, 30, &err);
  else
    video_ = render::make_png_sequence_sink(base + "_frames", w, h, "frame_", &err);
  if (!video_) {
    status("cannot record: " + err, true);
    return;
  }
  video_w_ = w;
  video_h_ = h;
  status(ffmpeg.empty() ? fmt::format("recording PNG frames to {}_frames/ (ffmpeg not found)", base)
                        : fmt::format("recording MP4 to {}.mp4 via ffmpeg", base));
}

void Viewer::capture(int fbw, int fbh) {
  if (pending_screenshot_.empty() && !video_) return;
  glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
  glReadBuffer(GL_BACK);
  auto px = render::read_framebuffer(fbw, fbh);
  if (!pending_screenshot_.empty()) {
    if (render::write_png(pending_screenshot_, fbw, fbh, px.data()))
      status("screenshot saved: " + pending_screenshot_);
    else
      status("cannot write " + pending_screenshot_, true);
    pending_screenshot_.clear();
  }
  if (video_) {
    if (fbw != video_w_ || fbh != video_h_) {
      status("window size changed: recording stopped");
      toggle_recording();
    } else if (!video_->write(px.data())) {
      status("recording failed: " + video_->error(), true);
      video_.reset();
    }
  }
}

}  // namespace rtsph::app
