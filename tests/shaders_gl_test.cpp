// Every shader in shaders/ compiles (and every program links) in a live OpenGL 4.3 context —
// the same embedded sources the binary uses. Build time also runs glslangValidator on them.
#include <gtest/gtest.h>

#include <filesystem>
#include <set>
#include <string>

#include "gl_test_context.h"
#include "render/gl_context.h"
#include "render/renderer.h"
#include "render/shader.h"

using namespace rtsph::render;

TEST(Shaders, EveryEmbeddedShaderCompiles) {
  std::unique_ptr<HeadlessContext> ctx;
  RTSPH_HEADLESS_CONTEXT_OR_SKIP(ctx);
  auto names = shader_names();
  ASSERT_GE(names.size(), 6u);
  for (const auto& n : names) {
    GLuint s = 0;
    EXPECT_NO_THROW(s = compile_shader(shader_stage(n), n, shader_source(n))) << n;
    if (s) glDeleteShader(s);
  }
  EXPECT_NO_THROW({ Renderer r; });  // links every program the renderer uses
}

TEST(Shaders, EveryFileInTheFolderIsEmbedded) {
  namespace fs = std::filesystem;
  std::set<std::string> embedded;
  for (const auto& n : shader_names()) embedded.insert(n);
  for (const auto& e : fs::directory_iterator(fs::path(RTSPH_SOURCE_DIR) / "shaders")) {
    auto ext = e.path().extension().string();
    if (ext == ".vert" || ext == ".frag" || ext == ".comp") {
      EXPECT_TRUE(embedded.count(e.path().filename().string())) << e.path();
    }
  }
}

TEST(Shaders, BrokenSourceReportsTheLog) {
  std::unique_ptr<HeadlessContext> ctx;
  RTSPH_HEADLESS_CONTEXT_OR_SKIP(ctx);
  try {
    compile_shader(GL_FRAGMENT_SHADER, "broken.frag", "#version 430 core\nvoid main() { x = 1; }\n");
    FAIL() << "expected a compile error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("broken.frag"), std::string::npos);
  }
}
