#pragma once
// An offscreen framebuffer whose attachments are sampled by later passes: colour textures of
// one format and an optional depth texture (or a depth renderbuffer when only tested). Resized
// on demand; the surface passes keep one per intermediate image.
#include <epoxy/gl.h>

namespace rtsph::render {

class TextureTarget {
 public:
  enum class Depth { None, Renderbuffer, Texture };
  /// linear: the colour textures are sampled with bilinear filtering (else nearest texels).
  /// color2_format: a second colour attachment of that format (0: none).
  TextureTarget(GLenum color_format, Depth depth, bool linear, GLenum color2_format = 0)
      : format_(color_format), format2_(color2_format), depth_kind_(depth), linear_(linear) {}
  ~TextureTarget();
  TextureTarget(const TextureTarget&) = delete;
  TextureTarget& operator=(const TextureTarget&) = delete;

  /// (Re)allocates at w×h if the size changed, binds the framebuffer and sets the viewport.
  void bind(int w, int h);
  GLuint color() const { return color_; }
  GLuint color2() const { return color2_; }
  GLuint depth() const { return depth_; }  // texture (Depth::Texture) or renderbuffer
  int width() const { return w_; }
  int height() const { return h_; }

 private:
  void release();
  GLenum format_, format2_;
  Depth depth_kind_;
  bool linear_;
  GLuint fbo_ = 0, color_ = 0, color2_ = 0, depth_ = 0;
  int w_ = 0, h_ = 0;
};

}  // namespace rtsph::render
