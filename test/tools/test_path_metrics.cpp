// Tests of the polyline metrics shared by tdo-plan and the bench (tools/tdo-plan/path_metrics.h).
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "path_metrics.h"

using tdo_tools::deflection_deg;
using tdo_tools::polyline_length;
using tdo_tools::turn_stats;

TEST(PathMetrics, GivenFewerThanTwoPointsThenLengthAndTurnsAreZero) {
  EXPECT_DOUBLE_EQ(polyline_length({}), 0.0);
  EXPECT_DOUBLE_EQ(polyline_length({tdo_vec3{1, 2, 3}}), 0.0);
  EXPECT_EQ(turn_stats({}).turns, 0);
  EXPECT_EQ(turn_stats({tdo_vec3{1, 2, 3}, tdo_vec3{2, 2, 3}}).turns, 0);
}

TEST(PathMetrics, GivenGridStepsThenLengthIsTheSumOfStepLengths) {
  const std::vector<tdo_vec3> p{{0, 0, 0}, {1, 0, 0}, {2, 1, 0}, {3, 2, 1}};
  EXPECT_NEAR(polyline_length(p), 1.0 + std::sqrt(2.0) + std::sqrt(3.0), 1e-12);
}

TEST(PathMetrics, GivenStraightLineThenNoTurns) {
  const std::vector<tdo_vec3> p{{0, 0, 0}, {1, 1, 1}, {2, 2, 2}, {2, 2, 2}, {3, 3, 3}};
  const auto s = turn_stats(p);
  EXPECT_EQ(s.turns, 0);
  EXPECT_DOUBLE_EQ(s.total_turn_deg, 0.0);
}

TEST(PathMetrics, GivenRightAngleAndDiagonalTurnsThenDeflectionsAreCountedInDegrees) {
  EXPECT_NEAR(deflection_deg({0, 0, 0}, {1, 0, 0}, {1, 1, 0}), 90.0, 1e-12);
  EXPECT_NEAR(deflection_deg({0, 0, 0}, {1, 0, 0}, {2, 1, 0}), 45.0, 1e-12);
  EXPECT_NEAR(deflection_deg({0, 0, 0}, {1, 0, 0}, {0, 0, 0}), 180.0, 1e-12);
  // square corner, then 45 degrees, with a repeated point in between that must not count
  const std::vector<tdo_vec3> p{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {1, 1, 0}, {2, 2, 0}};
  const auto s = turn_stats(p);
  EXPECT_EQ(s.turns, 2);
  EXPECT_NEAR(s.total_turn_deg, 135.0, 1e-9);
}

TEST(PathMetrics, GivenDeflectionBelowOneDegreeThenItIsNotATurn) {
  const double small = std::tan(0.5 * 3.14159265358979323846 / 180.0);  // 0.5 degree
  const std::vector<tdo_vec3> p{{0, 0, 0}, {1, 0, 0}, {2, small, 0}};
  EXPECT_EQ(turn_stats(p).turns, 0);
  EXPECT_EQ(turn_stats(p, 0.25).turns, 1);
}
