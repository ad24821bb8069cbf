// docs/scene-format.md must be exactly what scene_format_markdown() generates, so the reference
// cannot drift from the parser. To refresh it: RTSPH_UPDATE_DOCS=1 ./scene_docs_test
#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>
#include <sstream>

#include "scene/params.h"
#include "scene/scene.h"

namespace rtsph {
namespace {

const std::string kDocPath = std::string(RTSPH_SOURCE_DIR) + "/docs/scene-format.md";

TEST(SceneDocs, CommittedReferenceMatchesTheTable) {
  const std::string generated = scene_format_markdown();
  if (std::getenv("RTSPH_UPDATE_DOCS")) std::ofstream(kDocPath, std::ios::binary) << generated;
  std::ifstream in(kDocPath, std::ios::binary);
  ASSERT_TRUE(in) << kDocPath;
  std::stringstream committed;
  committed << in.rdbuf();
  EXPECT_TRUE(committed.str() == generated)
      << kDocPath << " is stale; regenerate with RTSPH_UPDATE_DOCS=1 ./scene_docs_test "
      << "or `rtsph scenes --markdown > docs/scene-format.md`";
}

TEST(SceneDocs, EveryKeyAndBuiltinIsDocumented) {
  const std::string doc = scene_format_markdown();
  for (const auto& p : parameter_table()) EXPECT_NE(doc.find("`" + p.key + "`"), std::string::npos) << p.key;
  for (const auto& f : emitter_fields()) EXPECT_NE(doc.find("`" + f.key + "`"), std::string::npos) << f.key;
  for (const auto& [name, _] : builtin_scenes()) EXPECT_NE(doc.find("`" + name + "`"), std::string::npos) << name;
}

}  // namespace
}  // namespace rtsph
