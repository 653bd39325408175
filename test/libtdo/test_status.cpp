// tdo_status_str: a stable lower_snake name for every status (status.h).
#include <gtest/gtest.h>

#include <cstring>
#include <set>
#include <string>

#include "tdo/status.h"

namespace {

bool is_lower_snake(const std::string& s) {
  if (s.empty() || s.front() == '_' || s.back() == '_') return false;
  if (!(s.front() >= 'a' && s.front() <= 'z')) return false;
  for (size_t n = 0; n < s.size(); ++n) {
    const char c = s[n];
    const bool ok = (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_';
    if (!ok) return false;
    if (c == '_' && n > 0 && s[n - 1] == '_') return false;
  }
  return true;
}

TEST(Status, GivenEveryStatusBelowCount_WhenNamed_ThenNameIsNonEmptyLowerSnake) {
  for (int s = 0; s < TDO_STATUS_COUNT; ++s) {
    const char* name = tdo_status_str(static_cast<tdo_status>(s));
    ASSERT_NE(name, nullptr) << "status " << s;
    EXPECT_TRUE(is_lower_snake(name)) << "status " << s << " has name '" << name << "'";
  }
}

TEST(Status, GivenEveryStatusBelowCount_WhenNamed_ThenNamesAreDistinctAndNotUnknown) {
  std::set<std::string> seen;
  for (int s = 0; s < TDO_STATUS_COUNT; ++s) {
    const char* name = tdo_status_str(static_cast<tdo_status>(s));
    ASSERT_NE(name, nullptr);
    EXPECT_STRNE(name, "unknown_status") << "status " << s << " has no name of its own";
    EXPECT_TRUE(seen.insert(name).second) << "status " << s << " repeats name '" << name << "'";
  }
  EXPECT_EQ(seen.size(), static_cast<size_t>(TDO_STATUS_COUNT));
}

TEST(Status, GivenTheEnumIdentifiers_WhenNamed_ThenNameIsTheIdentifierWithoutPrefix) {
  // The names are the stable strings scripts see (tdo-plan --json "status"): the enum identifier,
  // lower-cased, without TDO_ / TDO_ERR_ (status.h: e.g. "start_blocked"; docs/design.md s.10:
  // "ok").
  struct Expect {
    tdo_status status;
    const char* name;
  };
  const Expect table[] = {
      {TDO_OK, "ok"},
      {TDO_ERR_INVALID_ARGUMENT, "invalid_argument"},
      {TDO_ERR_ARENA_TOO_SMALL, "arena_too_small"},
      {TDO_ERR_MAP_CAPACITY, "map_capacity"},
      {TDO_ERR_BOX_CAPACITY, "box_capacity"},
      {TDO_ERR_INVALID_BOX, "invalid_box"},
      {TDO_ERR_MAP_NOT_READY, "map_not_ready"},
      {TDO_ERR_START_OUT_OF_BOUNDS, "start_out_of_bounds"},
      {TDO_ERR_GOAL_OUT_OF_BOUNDS, "goal_out_of_bounds"},
      {TDO_ERR_START_BLOCKED, "start_blocked"},
      {TDO_ERR_GOAL_BLOCKED, "goal_blocked"},
      {TDO_ERR_START_EQUALS_GOAL, "start_equals_goal"},
      {TDO_ERR_NO_PATH, "no_path"},
      {TDO_ERR_NODE_CAPACITY, "node_capacity"},
      {TDO_ERR_PATH_CAPACITY, "path_capacity"},
      {TDO_ERR_BUDGET, "budget"},
      {TDO_ERR_INFEASIBLE, "infeasible"},
      {TDO_ERR_LOCAL_MINIMUM, "local_minimum"},
      {TDO_ERR_OBSTACLE_CAPACITY, "obstacle_capacity"},
      {TDO_ERR_SAMPLE_CAPACITY, "sample_capacity"},
      {TDO_ERR_CLEARANCE_CAPACITY, "clearance_capacity"},
      {TDO_ERR_NOT_CONFIGURED, "not_configured"},
      {TDO_ERR_OPEN_CAPACITY, "open_capacity"},
      {TDO_ERR_UPDATE_CONTRADICTORY, "update_contradictory"},
      {TDO_ERR_STATE_NOT_FINITE, "state_not_finite"},
      {TDO_ERR_STATE_TOO_FAST, "state_too_fast"},
      {TDO_ERR_STATE_OVER_LIMITS, "state_over_limits"},
      {TDO_ERR_STATE_CANNOT_STOP, "state_cannot_stop"},
      {TDO_ERR_SETPOINT_STALE, "setpoint_stale"},
  };
  EXPECT_EQ(sizeof(table) / sizeof(table[0]), static_cast<size_t>(TDO_STATUS_COUNT))
      << "a status was added to status.h without a name in this table";
  for (const Expect& e : table) EXPECT_STREQ(tdo_status_str(e.status), e.name);
}

TEST(Status, GivenValuesOutsideTheEnum_WhenNamed_ThenUnknownStatus) {
  // Values up to 31 stay inside the value range of the enum type (no UB in C++, even under UBSan).
  for (int s = TDO_STATUS_COUNT; s < 32; ++s) {
    const char* name = tdo_status_str(static_cast<tdo_status>(s));
    ASSERT_NE(name, nullptr) << "value " << s;
    EXPECT_STREQ(name, "unknown_status") << "value " << s;
  }
}

}  // namespace
