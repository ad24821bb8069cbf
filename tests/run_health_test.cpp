// The instability guard (solvers/health.h): healthy runs pass, NaN/Inf and runaway compression
// are found within the step, and the diagnostic names the particle, dt and the likely cause.
#include <cmath>
#include <cstring>
#include <limits>
#include <string>

#include <gtest/gtest.h>

#include "solvers/health.h"
#include "test_scenes.h"

namespace rtsph {
namespace {

/// The named float state field (e.g. "fluid.v.y") of a simulation, writable.
float* field(Simulation& sim, const std::string& name) {
  for (const auto& f : sim.state_fields())
    if (f.name == name) return static_cast<float*>(f.data);
  ADD_FAILURE() << "no field " << name;
  return nullptr;
}

TEST(Health, HealthyDamBreakPasses) {
  auto sim = make_simulation(test::dam_break_2d(0.5, 0.02), 1);
  EXPECT_FALSE(check_health(*sim).has_value());
  for (int i = 0; i < 100; ++i) {
    sim->step();
    ASSERT_FALSE(check_health(*sim).has_value()) << *check_health_message(*sim);
  }
}

TEST(Health, FindsNaNVelocityAndNamesTheParticle) {
  auto sim = make_simulation(test::dam_break_2d(0.5, 0.02), 1);
  sim->step();
  const auto view = sim->fluid();
  const std::size_t i = view.count / 2;
  const std::uint32_t id = view.id[i];
  field(*sim, "fluid.v.y")[i] = std::numeric_limits<float>::quiet_NaN();
  const auto issue = check_health(*sim);
  ASSERT_TRUE(issue.has_value());
  EXPECT_EQ(issue->kind, HealthIssue::Kind::NonFinite);
  EXPECT_EQ(issue->quantity, "velocity");
  EXPECT_EQ(issue->id, id);
  EXPECT_EQ(issue->index, i);
  EXPECT_EQ(issue->position[0], double(view.x[0][i]));
  EXPECT_EQ(issue->step, 1u);
  EXPECT_NE(issue->message.find("particle " + std::to_string(id)), std::string::npos) << issue->message;
  EXPECT_NE(issue->message.find("step 1"), std::string::npos) << issue->message;
  EXPECT_NE(issue->message.find("dt = "), std::string::npos) << issue->message;
}

TEST(Health, FindsInfinitePressureAndNaNPosition) {
  auto sim = make_simulation(test::dam_break_2d(0.5, 0.02), 1);
  field(*sim, "fluid.p")[3] = std::numeric_limits<float>::infinity();
  auto issue = check_health(*sim);
  ASSERT_TRUE(issue.has_value());
  EXPECT_EQ(issue->quantity, "pressure");
  EXPECT_TRUE(std::isinf(issue->value));

  auto sim2 = make_simulation(test::dam_break_2d(0.5, 0.02), 1);
  field(*sim2, "fluid.x.x")[7] = -std::numeric_limits<float>::quiet_NaN();
  issue = check_health(*sim2);
  ASSERT_TRUE(issue.has_value());
  EXPECT_EQ(issue->quantity, "position");
  EXPECT_EQ(issue->index, 7u);
}

TEST(Health, CompressionLimitIsAParameter) {
  auto sim = make_simulation(test::dam_break_2d(0.5, 0.02), 1);
  float* rho = field(*sim, "fluid.rho");
  rho[10] = 1300.f;  // 30 % compression (ρ0 = 1000)
  EXPECT_FALSE(check_health(*sim, 0.5).has_value());
  const auto issue = check_health(*sim, 0.2);
  ASSERT_TRUE(issue.has_value());
  EXPECT_EQ(issue->kind, HealthIssue::Kind::Compression);
  EXPECT_NEAR(issue->value, 0.3, 1e-6);
  EXPECT_EQ(issue->index, 10u);
  EXPECT_NE(issue->message.find("density error 30 %"), std::string::npos) << issue->message;
}

TEST(Health, TooLargeFixedDtIsCaughtWithinAFewStepsAndBlamed) {
  SimSpec s = test::dam_break_2d(0.5, 0.02);
  s.time_step_mode = TimeStepMode::Fixed;
  s.dt = 0.005;  // ~40x the acoustic limit
  auto sim = make_simulation(s, 1);
  std::optional<HealthIssue> issue;
  int steps = 0;
  while (!issue && steps < 50) {
    sim->step();
    ++steps;
    issue = check_health(*sim);
  }
  ASSERT_TRUE(issue.has_value()) << "50 steps at dt = 0.005 s should blow up";
  EXPECT_LT(steps, 20);
  EXPECT_EQ(issue->dt_s, 0.005);
  EXPECT_NE(issue->cause.find("above the CFL limit"), std::string::npos) << issue->cause;
  EXPECT_NE(issue->cause.find("c0 = "), std::string::npos) << issue->cause;
  EXPECT_NE(issue->cause.find("solver.time_step.dt"), std::string::npos) << issue->cause;
  std::printf("diagnostic after %d steps: %s\n", steps, issue->message.c_str());
}

TEST(Health, SoftFluidIsBlamedOnTheSpeedOfSound) {
  SimSpec s = test::dam_break_2d(0.5, 0.02);
  s.speed_of_sound = 2.0;  // the fall alone reaches ~3 m/s
  auto sim = make_simulation(s, 1);
  std::optional<HealthIssue> issue;
  for (int i = 0; i < 20000 && !issue && sim->time() < 1.0; ++i) {
    sim->step();
    issue = check_health(*sim, 0.2);
  }
  ASSERT_TRUE(issue.has_value());
  EXPECT_EQ(issue->kind, HealthIssue::Kind::Compression);
  EXPECT_NE(issue->cause.find("speed of sound"), std::string::npos) << issue->cause;
}

TEST(Health, MessageHelperMatches) {
  auto sim = make_simulation(test::dam_break_2d(0.5, 0.02), 1);
  EXPECT_FALSE(check_health_message(*sim).has_value());
  field(*sim, "fluid.rho")[0] = std::numeric_limits<float>::quiet_NaN();
  const auto msg = check_health_message(*sim);
  ASSERT_TRUE(msg.has_value());
  EXPECT_EQ(*msg, check_health(*sim)->message);
  EXPECT_EQ(msg->find('\n'), std::string::npos);
}

}  // namespace
}  // namespace rtsph
