#pragma once
// Bitwise comparison of two simulations' complete state (every checkpoint field), shared by the
// resume and determinism tests.
#include <gtest/gtest.h>

#include <string>
#include <utility>
#include <vector>

#include "solvers/simulation.h"

namespace rtsph::test {

/// Every state field as (name, bytes).
inline std::vector<std::pair<std::string, std::string>> state_of(Simulation& sim) {
  std::vector<std::pair<std::string, std::string>> out;
  for (const auto& f : sim.state_fields())
    out.emplace_back(f.name, std::string(static_cast<const char*>(f.data), f.bytes));
  return out;
}

inline void expect_same_state(Simulation& a, Simulation& b) {
  const auto sa = state_of(a), sb = state_of(b);
  ASSERT_EQ(sa.size(), sb.size());
  for (std::size_t i = 0; i < sa.size(); ++i) {
    EXPECT_EQ(sa[i].first, sb[i].first);
    EXPECT_TRUE(sa[i].second == sb[i].second) << "field " << sa[i].first << " differs";
  }
  EXPECT_EQ(a.step_count(), b.step_count());
  EXPECT_EQ(a.time(), b.time());
}

}  // namespace rtsph::test
