#include "render/surface_target.h"

#include <stdexcept>

#include <fmt/format.h>

namespace rtsph::render {

namespace {
void texture_params(GLint filter) {
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, filter);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, filter);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
}
}  // namespace

TextureTarget::~TextureTarget() { release(); }

void TextureTarget::release() {
  if (fbo_) glDeleteFramebuffers(1, &fbo_);
  if (color_) glDeleteTextures(1, &color_);
  if (color2_) glDeleteTextures(1, &color2_);
  if (depth_ && depth_kind_ == Depth::Texture) glDeleteTextures(1, &depth_);
  if (depth_ && depth_kind_ == Depth::Renderbuffer) glDeleteRenderbuffers(1, &depth_);
  fbo_ = color_ = color2_ = depth_ = 0;
  w_ = h_ = 0;
}

void TextureTarget::bind(int w, int h) {
  if (w != w_ || h != h_ || !fbo_) {
    release();
    glGenFramebuffers(1, &fbo_);
    glBindFramebuffer(GL_FRAMEBUFFER, fbo_);
    // A unit of its own, so that allocating never unbinds a texture a pass has bound.
    glActiveTexture(GL_TEXTURE15);
    glGenTextures(1, &color_);
    glBindTexture(GL_TEXTURE_2D, color_);
    glTexStorage2D(GL_TEXTURE_2D, 1, format_, w, h);
    texture_params(linear_ ? GL_LINEAR : GL_NEAREST);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, color_, 0);
    if (format2_) {
      glGenTextures(1, &color2_);
      glBindTexture(GL_TEXTURE_2D, color2_);
      glTexStorage2D(GL_TEXTURE_2D, 1, format2_, w, h);
      texture_params(linear_ ? GL_LINEAR : GL_NEAREST);
      glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT1, GL_TEXTURE_2D, color2_, 0);
      const GLenum buffers[2] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1};
      glDrawBuffers(2, buffers);
    }
    if (depth_kind_ == Depth::Texture) {
      glGenTextures(1, &depth_);
      glBindTexture(GL_TEXTURE_2D, depth_);
      glTexStorage2D(GL_TEXTURE_2D, 1, GL_DEPTH_COMPONENT24, w, h);
      texture_params(GL_NEAREST);
      glFramebufferTexture2D(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_TEXTURE_2D, depth_, 0);
    } else if (depth_kind_ == Depth::Renderbuffer) {
      glGenRenderbuffers(1, &depth_);
      glBindRenderbuffer(GL_RENDERBUFFER, depth_);
      glRenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT24, w, h);
      glBindRenderbuffer(GL_RENDERBUFFER, 0);
      glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, depth_);
    }
    glBindTexture(GL_TEXTURE_2D, 0);
    glActiveTexture(GL_TEXTURE0);
    const GLenum status = glCheckFramebufferStatus(GL_FRAMEBUFFER);
    if (status != GL_FRAMEBUFFER_COMPLETE) {
      release();
      glBindFramebuffer(GL_FRAMEBUFFER, 0);
      throw std::runtime_error(fmt::format("surface target {}x{} incomplete (0x{:x})", w, h,
                                           static_cast<unsigned>(status)));
    }
    w_ = w;
    h_ = h;
  }
  glBindFramebuffer(GL_FRAMEBUFFER, fbo_);
  glViewport(0, 0, w, h);
}

}  // namespace rtsph::render
