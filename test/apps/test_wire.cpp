// Wire checks and safe decoding of received bytes (apps/common wire.h): every malformed message is
// refused with a name, never decoded into a crash or a huge allocation.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include "rng.h"
#include "tdo_lcm/types.h"
#include "tdo_lcm/wire.h"

namespace {

using tdo_lcm::Reason;

template <class Msg>
std::vector<uint8_t> encode(const Msg& m) {
  std::vector<uint8_t> buf(static_cast<std::size_t>(m.getEncodedSize()));
  EXPECT_EQ(m.encode(buf.data(), 0, static_cast<int>(buf.size())), static_cast<int>(buf.size()));
  return buf;
}

void put_be32(std::vector<uint8_t>* buf, std::size_t pos, uint32_t v) {
  for (int i = 0; i < 4; ++i)
    (*buf)[pos + static_cast<std::size_t>(i)] = static_cast<uint8_t>(v >> (24 - 8 * i));
}

tdo::status_t sample_status() {
  tdo::status_t s{};
  s.utime = 1234;
  s.seq = 7;
  s.program = "tdo-planner";
  s.vehicle_id = 3;
  s.uptime_s = 1.5;
  s.map_id = 2;
  s.reason = {"request.non_finite", "map.truncated"};
  s.reason_count = {4, 5};
  s.n_reasons = 2;
  return s;
}

tdo::obstacles_t sample_obstacles(tdo_test::Rng* rng, int32_t n) {
  tdo::obstacles_t o{};
  o.utime = 99;
  o.seq = 1;
  o.vehicle_id = -1;
  o.n = n;
  for (int32_t i = 0; i < n; ++i) {
    o.id.push_back(i);
    o.position.push_back({rng->uniform(), rng->uniform(), rng->uniform()});
    o.velocity.push_back({rng->uniform(), rng->uniform(), rng->uniform()});
    o.radius.push_back(0.5);
  }
  return o;
}

// Byte offset of obstacles_t.n: fingerprint 8, utime 8, seq 8, vehicle_id 4.
constexpr std::size_t kObstaclesCountAt = 28;

TEST(Wire, FingerprintsMatchTheCppTypes) {
  EXPECT_EQ(tdo_lcm::TypeInfo<tdo::map_t>::get()->get_hash(), tdo::map_t::getHash());
  EXPECT_EQ(tdo_lcm::TypeInfo<tdo::plan_request_t>::get()->get_hash(),
            tdo::plan_request_t::getHash());
  EXPECT_EQ(tdo_lcm::TypeInfo<tdo::trajectory_t>::get()->get_hash(), tdo::trajectory_t::getHash());
  EXPECT_EQ(tdo_lcm::TypeInfo<tdo::feasibility_t>::get()->get_hash(),
            tdo::feasibility_t::getHash());
  EXPECT_EQ(tdo_lcm::TypeInfo<tdo::status_t>::get()->get_hash(), tdo::status_t::getHash());
  EXPECT_EQ(tdo_lcm::TypeInfo<tdo::obstacles_t>::get()->get_hash(), tdo::obstacles_t::getHash());
  EXPECT_EQ(tdo_lcm::TypeInfo<tdo::vehicle_state_t>::get()->get_hash(),
            tdo::vehicle_state_t::getHash());
  EXPECT_EQ(tdo_lcm::TypeInfo<tdo::setpoint_t>::get()->get_hash(), tdo::setpoint_t::getHash());
}

TEST(Wire, RoundTripsOfEveryShape) {
  tdo_test::Rng rng(11);
  // Strings and string arrays.
  const tdo::status_t s = sample_status();
  std::vector<uint8_t> buf = encode(s);
  tdo::status_t s2{};
  ASSERT_TRUE(tdo_lcm::decode(buf.data(), buf.size(), &s2).ok());
  EXPECT_EQ(s2.reason, s.reason);
  EXPECT_EQ(s2.reason_count, s.reason_count);
  EXPECT_EQ(s2.program, s.program);
  // Two-dimensional arrays with a variable first dimension, several sizes including 0.
  for (int32_t n : {0, 1, 7, 300}) {
    const tdo::obstacles_t o = sample_obstacles(&rng, n);
    buf = encode(o);
    tdo::obstacles_t o2{};
    ASSERT_TRUE(tdo_lcm::decode(buf.data(), buf.size(), &o2).ok()) << n;
    EXPECT_EQ(o2.position, o.position);
    EXPECT_EQ(o2.radius, o.radius);
  }
  // Byte arrays, int32 arrays, fixed arrays.
  tdo::map_t m{};
  m.map_id = 4;
  m.size[0] = 2;
  m.size[1] = 3;
  m.size[2] = 4;
  m.n_runs = 3;
  m.runs = {1, 2, 21};
  m.n_bytes = 5;
  m.data = {1, 2, 3, 4, 5};
  m.n_boxes = 1;
  m.boxes = {{0, 0, 0, 1, 1, 1}};
  buf = encode(m);
  tdo::map_t m2{};
  ASSERT_TRUE(tdo_lcm::decode(buf.data(), buf.size(), &m2).ok());
  EXPECT_EQ(m2.runs, m.runs);
  EXPECT_EQ(m2.data, m.data);
  EXPECT_EQ(m2.boxes, m.boxes);
  EXPECT_EQ(m2.size[2], 4);
}

TEST(Wire, WrongFingerprint) {
  const std::vector<uint8_t> buf = encode(sample_status());
  tdo::plan_request_t r{};
  const tdo_lcm::Check c = tdo_lcm::decode(buf.data(), buf.size(), &r);
  EXPECT_EQ(c.reason, Reason::bad_fingerprint);
}

template <class Msg>
void expect_every_prefix_refused(const Msg& m) {
  const std::vector<uint8_t> full = encode(m);
  for (std::size_t len = 0; len < full.size(); ++len) {
    Msg out{};
    const tdo_lcm::Check c = tdo_lcm::decode(full.data(), len, &out);
    EXPECT_EQ(c.reason, Reason::truncated)
        << Msg::getTypeName() << ": length " << len << " of " << full.size() << ": "
        << tdo_lcm::reason_str(c.reason) << " " << c.detail;
  }
}

TEST(Wire, EveryTruncationIsRefused) {
  tdo_test::Rng rng(3);
  expect_every_prefix_refused(sample_status());
  expect_every_prefix_refused(sample_obstacles(&rng, 4));
  tdo::trajectory_t t{};
  t.status = "ok";
  t.n_samples = 2;
  t.samples = {std::vector<double>(10, 1.0), std::vector<double>(10, 2.0)};
  expect_every_prefix_refused(t);
}

TEST(Wire, TrailingBytes) {
  std::vector<uint8_t> buf = encode(sample_status());
  buf.push_back(0);
  tdo::status_t s{};
  EXPECT_EQ(tdo_lcm::decode(buf.data(), buf.size(), &s).reason, Reason::trailing_bytes);
}

TEST(Wire, NegativeAndHugeCountsNeverReachTheDecoder) {
  tdo_test::Rng rng(4);
  const std::vector<uint8_t> good = encode(sample_obstacles(&rng, 2));
  tdo::obstacles_t o{};
  std::vector<uint8_t> buf = good;
  put_be32(&buf, kObstaclesCountAt, 0xFFFFFFFFu);  // n = -1
  EXPECT_EQ(tdo_lcm::decode(buf.data(), buf.size(), &o).reason, Reason::negative_count);
  put_be32(&buf, kObstaclesCountAt, 0x7FFFFFFFu);  // n = INT32_MAX: gigabytes if decoded blindly
  EXPECT_EQ(tdo_lcm::decode(buf.data(), buf.size(), &o).reason, Reason::truncated);
  put_be32(&buf, kObstaclesCountAt, 3u);  // one more than the bytes hold
  EXPECT_EQ(tdo_lcm::decode(buf.data(), buf.size(), &o).reason, Reason::truncated);
  put_be32(&buf, kObstaclesCountAt, 1u);  // fewer: bytes left over
  EXPECT_EQ(tdo_lcm::decode(buf.data(), buf.size(), &o).reason, Reason::trailing_bytes);
}

TEST(Wire, BadStrings) {
  const std::vector<uint8_t> good = encode(sample_status());
  // status_t.program: its length follows fingerprint 8, utime 8, seq 8.
  const std::size_t at = 24;
  tdo::status_t s{};
  std::vector<uint8_t> buf = good;
  put_be32(&buf, at, 0u);  // length 0: lcm-gen's decoder would assign a string of size_t(-1)
  EXPECT_EQ(tdo_lcm::decode(buf.data(), buf.size(), &s).reason, Reason::bad_string);
  buf = good;
  buf[at + 4 + std::strlen("tdo-planner")] = 'x';  // no terminating zero
  EXPECT_EQ(tdo_lcm::decode(buf.data(), buf.size(), &s).reason, Reason::bad_string);
  buf = good;
  put_be32(&buf, at, 0x7FFFFFF0u);
  EXPECT_EQ(tdo_lcm::decode(buf.data(), buf.size(), &s).reason, Reason::truncated);
}

TEST(Wire, SeededRandomCorruptionNeverCrashes) {
  // Flip random bytes of valid messages: whatever comes out is either refused by name or decodes
  // to a message that re-encodes to the same bytes.
  tdo_test::Rng rng(8);
  const std::vector<uint8_t> base = encode(sample_obstacles(&rng, 3));
  for (int round = 0; round < 3000; ++round) {
    std::vector<uint8_t> buf = base;
    const int flips = 1 + static_cast<int>(rng.below(4));
    for (int f = 0; f < flips; ++f)
      buf[8 + rng.below(static_cast<uint32_t>(buf.size() - 8))] ^=
          static_cast<uint8_t>(1u + rng.below(255));
    tdo::obstacles_t o{};
    const tdo_lcm::Check c = tdo_lcm::decode(buf.data(), buf.size(), &o);
    if (c.ok()) {
      const std::vector<uint8_t> again = encode(o);
      EXPECT_EQ(again, buf) << "round " << round;
    }
  }
}

}  // namespace
