// Run-length encoding of voxel maps (apps/common rle.h).
#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

#include "rng.h"
#include "tdo_lcm/rle.h"

namespace {

using tdo_lcm::Reason;

TEST(Rle, KnownRuns) {
  // GIVEN occupancy 0 0 1 1 1 0 1  WHEN encoded  THEN free 2, occupied 3, free 1, occupied 1
  EXPECT_EQ(tdo_lcm::rle_encode({0, 0, 1, 1, 1, 0, 1}), (std::vector<int32_t>{2, 3, 1, 1}));
  // A map starting with an occupied voxel starts with an empty free run.
  EXPECT_EQ(tdo_lcm::rle_encode({1, 1, 0}), (std::vector<int32_t>{0, 2, 1}));
  EXPECT_EQ(tdo_lcm::rle_encode({0, 0, 0}), (std::vector<int32_t>{3}));
  EXPECT_EQ(tdo_lcm::rle_encode({}), (std::vector<int32_t>{}));
}

TEST(Rle, SeededRandomRoundTrips) {
  tdo_test::Rng rng(5);
  for (int round = 0; round < 300; ++round) {
    const std::size_t n = 1 + rng.below(2000);
    const double density = rng.uniform();
    std::vector<uint8_t> occ(n);
    for (auto& v : occ) v = rng.uniform() < density ? 1u : 0u;
    const std::vector<int32_t> runs = tdo_lcm::rle_encode(occ);
    uint64_t occupied = 0;
    ASSERT_TRUE(tdo_lcm::rle_check(runs, n, &occupied).ok()) << "round " << round;
    uint64_t expected = 0;
    for (uint8_t v : occ) expected += v;
    EXPECT_EQ(occupied, expected);
    EXPECT_EQ(tdo_lcm::rle_decode(runs, n), occ) << "round " << round;
    // Only the first run may be zero.
    for (std::size_t r = 1; r < runs.size(); ++r) EXPECT_GT(runs[r], 0);
  }
}

TEST(Rle, RunsLongerThanInt32AreSplitWithZeroRuns) {
  tdo_lcm::RleEncoder enc;
  const uint64_t long_run = 0x7FFFFFFFull + 5u;
  enc.push_run(false, long_run);
  enc.push_run(true, 3);
  const std::vector<int32_t> runs = enc.runs();
  EXPECT_EQ(runs, (std::vector<int32_t>{0x7FFFFFFF, 0, 5, 3}));
  uint64_t occupied = 0;
  EXPECT_TRUE(tdo_lcm::rle_check(runs, long_run + 3u, &occupied).ok());
  EXPECT_EQ(occupied, 3u);
  std::vector<uint64_t> seen;
  tdo_lcm::rle_for_each_occupied(runs, [&](uint64_t i) {
    seen.push_back(i);
    return true;
  });
  EXPECT_EQ(seen, (std::vector<uint64_t>{long_run, long_run + 1u, long_run + 2u}));
}

TEST(Rle, CheckNamesTheProblem) {
  EXPECT_EQ(tdo_lcm::rle_check({2, 3}, 6, nullptr).reason, Reason::rle_mismatch);
  EXPECT_EQ(tdo_lcm::rle_check({2, 5}, 6, nullptr).reason, Reason::rle_mismatch);
  const tdo_lcm::Check neg = tdo_lcm::rle_check({2, -1, 5}, 6, nullptr);
  EXPECT_EQ(neg.reason, Reason::out_of_range);
  EXPECT_NE(neg.detail.find("runs[1]"), std::string::npos) << neg.detail;
  // No runs: every voxel free.
  EXPECT_TRUE(tdo_lcm::rle_check({}, 1000, nullptr).ok());
}

TEST(Rle, ForEachStopsWhenAsked) {
  int calls = 0;
  const bool done = tdo_lcm::rle_for_each_occupied({0, 10}, [&](uint64_t) { return ++calls < 3; });
  EXPECT_FALSE(done);
  EXPECT_EQ(calls, 3);
}

}  // namespace
