// Vehicle adapters (vehicle.h): vehicle_state_t, setpoint_t, obstacles_t <-> libtdo structs, with
// every refusal named.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "tdo/tdo.h"
#include "tdo_lcm/adapters.h"
#include "tdo_lcm/vehicle.h"
#include "tdo_lcm/wire.h"

namespace {

using tdo_lcm::Check;
using tdo_lcm::Reason;

constexpr int64_t kRef = 1767225600000000;  // 2026-01-01 in us
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

void expect_refused(const Check& c, Reason r, const std::string& field) {
  EXPECT_EQ(c.reason, r) << tdo_lcm::reason_str(c.reason) << ": " << c.detail;
  EXPECT_NE(c.detail.find(field), std::string::npos) << c.detail;
}

tdo::vehicle_state_t state_msg() {
  tdo::vehicle_state_t m{};
  m.utime = kRef + 1234567;
  m.seq = 7;
  m.vehicle_id = 2;
  const double p[3] = {1.5, -2.25, 3.0}, v[3] = {0.5, 0.25, -0.125}, a[3] = {-1.0, 0.0, 2.0};
  for (int i = 0; i < 3; ++i) {
    m.position[i] = p[i];
    m.velocity[i] = v[i];
    m.acceleration[i] = a[i];
  }
  m.yaw = 0.75;
  return m;
}

tdo::obstacles_t obstacles_msg(int n) {
  tdo::obstacles_t m{};
  m.utime = kRef;
  m.vehicle_id = -1;
  m.n = n;
  for (int i = 0; i < n; ++i) {
    m.id.push_back(10 + i);
    m.position.push_back({1.0 * i, 2.0, 3.0});
    m.velocity.push_back({0.5, -0.5 * i, 0.0});
    m.radius.push_back(0.5 + 0.25 * i);
  }
  return m;
}

TEST(Clock, SecondsSinceAndBackAreExactToTheMicrosecond) {
  for (int64_t d :
       {int64_t{0}, int64_t{1}, int64_t{20000}, int64_t{-20000}, int64_t{123456789012}}) {
    const double t = tdo_lcm::seconds_since(kRef + d, kRef);
    EXPECT_EQ(tdo_lcm::utime_at(kRef, t), kRef + d) << d;
  }
  EXPECT_EQ(tdo_lcm::seconds_since(kRef + 20000, kRef), 0.02);
  // 1000 steps of 0.02 s land on whole microseconds.
  EXPECT_EQ(tdo_lcm::utime_at(kRef, 1000 * 0.02), kRef + 20000000);
  // Extremes saturate instead of overflowing; a NaN time does not move the reference.
  EXPECT_GT(tdo_lcm::seconds_since(std::numeric_limits<int64_t>::max(),
                                   std::numeric_limits<int64_t>::min()),
            9.0e12);
  EXPECT_EQ(tdo_lcm::utime_at(kRef, kNaN), kRef);
  EXPECT_EQ(tdo_lcm::utime_at(kRef, 1e300), kRef);
}

TEST(VehicleStateAdapter, RoundTrip) {
  const tdo::vehicle_state_t m = state_msg();
  tdo_vehicle_state s{};
  ASSERT_TRUE(tdo_lcm::vehicle_state_from_msg(m, 2, kRef, &s).ok());
  EXPECT_EQ(s.t, 1.234567);
  EXPECT_EQ(s.p.y, -2.25);
  EXPECT_EQ(s.v.z, -0.125);
  EXPECT_EQ(s.a.x, -1.0);
  tdo::vehicle_state_t back{};
  ASSERT_TRUE(tdo_lcm::vehicle_state_to_msg(s, kRef, 2, 7, 0.75, &back).ok());
  EXPECT_EQ(back.utime, m.utime);
  EXPECT_EQ(back.seq, 7);
  EXPECT_EQ(back.vehicle_id, 2);
  for (int i = 0; i < 3; ++i) {
    EXPECT_EQ(back.position[i], m.position[i]);
    EXPECT_EQ(back.velocity[i], m.velocity[i]);
    EXPECT_EQ(back.acceleration[i], m.acceleration[i]);
  }
  EXPECT_EQ(back.yaw, 0.75);
}

TEST(VehicleStateAdapter, RefusalsAreNamed) {
  tdo_vehicle_state s{};
  tdo::vehicle_state_t m = state_msg();
  expect_refused(tdo_lcm::vehicle_state_from_msg(m, 3, kRef, &s), Reason::other_vehicle,
                 "vehicle 2");
  m.position[1] = kNaN;
  m.vehicle_id = 9;  // the vehicle is checked first
  EXPECT_EQ(tdo_lcm::vehicle_state_from_msg(m, 3, kRef, &s).reason, Reason::other_vehicle);
  m.vehicle_id = 2;
  expect_refused(tdo_lcm::vehicle_state_from_msg(m, 2, kRef, &s), Reason::non_finite,
                 "position[1]");
  m = state_msg();
  m.velocity[2] = kInf;
  expect_refused(tdo_lcm::vehicle_state_from_msg(m, 2, kRef, &s), Reason::non_finite,
                 "velocity[2]");
  m = state_msg();
  m.acceleration[0] = -kInf;
  expect_refused(tdo_lcm::vehicle_state_from_msg(m, 2, kRef, &s), Reason::non_finite,
                 "acceleration[0]");
  m = state_msg();
  m.yaw = kNaN;
  expect_refused(tdo_lcm::vehicle_state_from_msg(m, 2, kRef, &s), Reason::non_finite, "yaw");
  // Outgoing: a non-finite state is refused and the message left alone.
  tdo_vehicle_state bad{};
  bad.v.y = kNaN;
  tdo::vehicle_state_t out = state_msg();
  expect_refused(tdo_lcm::vehicle_state_to_msg(bad, kRef, 2, 0, 0.0, &out), Reason::non_finite,
                 "velocity[1]");
  EXPECT_EQ(out.seq, 7);
}

TEST(SetpointAdapter, RoundTripAndRefusals) {
  tdo_setpoint sp{};
  sp.t = 0.04;
  sp.p = tdo_vec3{1, 2, 3};
  sp.v = tdo_vec3{0.1, 0.2, 0.3};
  sp.a = tdo_vec3{-0.5, 0.5, 0};
  tdo::setpoint_t m{};
  ASSERT_TRUE(
      tdo_lcm::setpoint_to_msg(sp, kRef + 20000, 4, 11, 99, 1.5, TDO_ERR_LOCAL_MINIMUM, &m).ok());
  EXPECT_EQ(m.utime, kRef + 20000);
  EXPECT_EQ(m.request_id, 99);
  EXPECT_EQ(m.status_code, static_cast<int32_t>(TDO_ERR_LOCAL_MINIMUM));
  EXPECT_EQ(m.status, tdo_status_str(TDO_ERR_LOCAL_MINIMUM));
  // Through the wire and back.
  std::vector<uint8_t> buf(static_cast<std::size_t>(m.getEncodedSize()));
  ASSERT_EQ(m.encode(buf.data(), 0, static_cast<int>(buf.size())), static_cast<int>(buf.size()));
  tdo::setpoint_t d{};
  ASSERT_TRUE(tdo_lcm::decode(buf.data(), buf.size(), &d).ok());
  tdo_setpoint back{};
  ASSERT_TRUE(tdo_lcm::setpoint_from_msg(d, 4, kRef, &back).ok());
  EXPECT_EQ(back.t, 0.02);  // the time it was computed at
  EXPECT_EQ(back.p.z, 3.0);
  EXPECT_EQ(back.v.y, 0.2);
  EXPECT_EQ(back.a.x, -0.5);

  expect_refused(tdo_lcm::setpoint_from_msg(d, 5, kRef, &back), Reason::other_vehicle, "vehicle 4");
  d.acceleration[2] = kNaN;
  expect_refused(tdo_lcm::setpoint_from_msg(d, 4, kRef, &back), Reason::non_finite,
                 "acceleration[2]");
  d.acceleration[2] = 0.0;
  d.yaw = kInf;
  expect_refused(tdo_lcm::setpoint_from_msg(d, 4, kRef, &back), Reason::non_finite, "yaw");
  sp.p.x = kInf;
  expect_refused(tdo_lcm::setpoint_to_msg(sp, kRef, 4, 0, -1, 0.0, TDO_OK, &m), Reason::non_finite,
                 "position[0]");
}

TEST(MoversAdapter, RoundTrip) {
  const tdo::obstacles_t m = obstacles_msg(3);
  std::vector<tdo_mover> mv;
  ASSERT_TRUE(tdo_lcm::movers_from_msg(m, 0, 8, &mv).ok());
  ASSERT_EQ(mv.size(), 3u);
  EXPECT_EQ(mv[2].id, 12u);
  EXPECT_EQ(mv[2].p.x, 2.0);
  EXPECT_EQ(mv[2].v.y, -1.0);
  EXPECT_EQ(mv[2].radius, 1.0);
  tdo::obstacles_t back{};
  ASSERT_TRUE(tdo_lcm::movers_to_msg(mv.data(), 3, kRef, -1, 5, &back).ok());
  EXPECT_EQ(back.n, 3);
  EXPECT_EQ(back.id, m.id);
  EXPECT_EQ(back.position, m.position);
  EXPECT_EQ(back.velocity, m.velocity);
  EXPECT_EQ(back.radius, m.radius);
  EXPECT_EQ(back.seq, 5);
  EXPECT_TRUE(tdo_lcm::check_counts(back).ok());
  // No movers is a valid message.
  ASSERT_TRUE(tdo_lcm::movers_to_msg(nullptr, 0, kRef, -1, 0, &back).ok());
  ASSERT_TRUE(tdo_lcm::movers_from_msg(back, 0, 8, &mv).ok());
  EXPECT_TRUE(mv.empty());
}

TEST(MoversAdapter, EveryMalformedMessageIsRefusedByName) {
  std::vector<tdo_mover> mv = {tdo_mover{1, {0, 0, 0}, {0, 0, 0}, 1.0}};
  tdo::obstacles_t m = obstacles_msg(2);
  m.vehicle_id = 3;
  expect_refused(tdo_lcm::movers_from_msg(m, 0, 8, &mv), Reason::other_vehicle, "vehicle 3");
  EXPECT_TRUE(tdo_lcm::movers_from_msg(m, 3, 8, &mv).ok());  // for this vehicle
  m = obstacles_msg(2);
  m.n = 3;  // counts that do not match the arrays
  expect_refused(tdo_lcm::movers_from_msg(m, 0, 8, &mv), Reason::count_mismatch, "id");
  m = obstacles_msg(2);
  m.radius.pop_back();
  expect_refused(tdo_lcm::movers_from_msg(m, 0, 8, &mv), Reason::count_mismatch, "radius");
  m = obstacles_msg(2);
  m.position[1].pop_back();
  expect_refused(tdo_lcm::movers_from_msg(m, 0, 8, &mv), Reason::count_mismatch, "position[1]");
  m = obstacles_msg(3);
  expect_refused(tdo_lcm::movers_from_msg(m, 0, 2, &mv), Reason::over_capacity, "capacity of 2");
  m = obstacles_msg(2);
  m.velocity[1][0] = kNaN;
  expect_refused(tdo_lcm::movers_from_msg(m, 0, 8, &mv), Reason::non_finite, "velocity[1][0]");
  m = obstacles_msg(2);
  m.position[0][2] = kInf;
  expect_refused(tdo_lcm::movers_from_msg(m, 0, 8, &mv), Reason::non_finite, "position[0][2]");
  m = obstacles_msg(2);
  m.radius[1] = kNaN;
  expect_refused(tdo_lcm::movers_from_msg(m, 0, 8, &mv), Reason::non_finite, "radius[1]");
  m = obstacles_msg(2);
  m.radius[0] = 0.0;
  expect_refused(tdo_lcm::movers_from_msg(m, 0, 8, &mv), Reason::out_of_range, "radius[0]");
  m = obstacles_msg(2);
  m.id[1] = -4;
  expect_refused(tdo_lcm::movers_from_msg(m, 0, 8, &mv), Reason::out_of_range, "id[1]");
  // A refused message leaves the output alone.
  ASSERT_EQ(mv.size(), 2u);
  EXPECT_EQ(mv[0].id, 10u);

  // Outgoing.
  tdo::obstacles_t out{};
  expect_refused(tdo_lcm::movers_to_msg(nullptr, 2, kRef, -1, 0, &out), Reason::count_mismatch,
                 "no array");
  mv[1].radius = -1.0;
  expect_refused(tdo_lcm::movers_to_msg(mv.data(), 2, kRef, -1, 0, &out), Reason::out_of_range,
                 "radius[1]");
  mv[1].radius = kInf;
  expect_refused(tdo_lcm::movers_to_msg(mv.data(), 2, kRef, -1, 0, &out), Reason::non_finite,
                 "radius[1]");
  mv[1].radius = 1.0;
  mv[0].p.y = kNaN;
  expect_refused(tdo_lcm::movers_to_msg(mv.data(), 2, kRef, -1, 0, &out), Reason::non_finite,
                 "position[0][1]");
  mv[0].p.y = 0.0;
  mv[0].id = 0x80000000u;
  expect_refused(tdo_lcm::movers_to_msg(mv.data(), 2, kRef, -1, 0, &out), Reason::too_large,
                 "id[0]");
}

TEST(MoversAdapter, AdvanceMovesOnAtConstantVelocityWithinTheClamp) {
  std::vector<tdo_mover> mv = {tdo_mover{1, {1, 2, 3}, {1, -2, 0.5}, 0.5}};
  tdo_lcm::movers_advance(&mv, 10.0, 10.5, 1.0);
  EXPECT_DOUBLE_EQ(mv[0].p.x, 1.5);
  EXPECT_DOUBLE_EQ(mv[0].p.y, 1.0);
  EXPECT_DOUBLE_EQ(mv[0].p.z, 3.25);
  tdo_lcm::movers_advance(&mv, 10.0, 15.0, 1.0);  // clamped to 1 s
  EXPECT_DOUBLE_EQ(mv[0].p.x, 2.5);
  tdo_lcm::movers_advance(&mv, 10.0, 9.0, 1.0);  // older state: no move backwards
  EXPECT_DOUBLE_EQ(mv[0].p.x, 2.5);
}

TEST(Heading, FromVelocityOrKept) {
  EXPECT_DOUBLE_EQ(tdo_lcm::heading_of(tdo_vec3{0, 1, 0}, 0.3), std::acos(0.0));
  EXPECT_DOUBLE_EQ(tdo_lcm::heading_of(tdo_vec3{0.01, 0.01, 5}, 0.3), 0.3);  // vertical: kept
  EXPECT_DOUBLE_EQ(tdo_lcm::heading_of(tdo_vec3{kNaN, 0, 0}, 0.3), 0.3);
}

}  // namespace
