// The parameter table's `live` flags and copy_live_parameters() (what Simulation::
// set_live_parameters applies) describe the same set: a parameter changed through the table is
// carried over by copy_live_parameters exactly when the table marks it live.
#include <gtest/gtest.h>

#include "scene/params.h"
#include "scene/scene.h"

namespace rtsph {
namespace {

/// Sets `p` in `s` to a valid value other than its default. False when there is none (an enum
/// with a single choice).
bool change(const ParamInfo& p, SimSpec& s) {
  switch (p.kind) {
    case ParamKind::Vec3: {
      Vec3d v = p.default_vec;
      for (int k = 0; k < 3; ++k) v[k] = v[k] + 0.5 <= p.max ? v[k] + 0.5 : v[k] - 0.5;
      p.set_vec(s, v);
      return true;
    }
    case ParamKind::String: p.set_text(s, p.default_text + "_changed"); return true;
    case ParamKind::Enum: {
      if (p.choices.size() < 2) return false;
      const std::size_t i = (std::size_t(p.default_value) + 1) % p.choices.size();
      if (p.set) p.set(s, double(i));
      else p.set_text(s, p.choices[i]);
      return true;
    }
    case ParamKind::Bool: p.set(s, 1 - p.default_value); return true;
    case ParamKind::Real:
    case ParamKind::Int:
      p.set(s, p.default_value != p.max ? p.max : p.min_exclusive ? (p.min + p.max) / 2 : p.min);
      return true;
  }
  return false;
}

TEST(LiveParams, TableFlagsMatchCopyLiveParameters) {
  int live = 0, fixed = 0;
  for (const ParamInfo& p : parameter_table()) {
    SCOPED_TRACE(p.key);
    SimSpec changed;
    if (!change(p, changed)) continue;
    ASSERT_NE(scene_to_json(changed), scene_to_json(SimSpec{})) << "the change did not take";
    SimSpec copied;
    copy_live_parameters(changed, copied);
    if (p.live) {
      EXPECT_EQ(scene_to_json(copied), scene_to_json(changed)) << "marked live but not copied";
      ++live;
    } else {
      EXPECT_EQ(scene_to_json(copied), scene_to_json(SimSpec{})) << "copied but not marked live";
      ++fixed;
    }
  }
  EXPECT_GT(live, 0);
  EXPECT_GT(fixed, 0);
}

}  // namespace
}  // namespace rtsph
