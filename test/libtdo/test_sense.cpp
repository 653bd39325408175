// Tests of the range sensor (sense.h): reveal within range and line of sight, occlusion, the
// nearest-box guarantee, capacity, bad input, and the map update it builds. The visibility checks
// use an independent segment/box model written from the header's definition.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <vector>

#include "rng.h"
#include "tdo/tdo.h"
#include "test_util.h"

namespace {

using tdo_test::TestPlanner;

double dist3(tdo_vec3 a, tdo_vec3 b) {
  return std::sqrt((a.x - b.x) * (a.x - b.x) + (a.y - b.y) * (a.y - b.y) +
                   (a.z - b.z) * (a.z - b.z));
}

tdo_vec3 closest(const tdo_box& b, tdo_vec3 p) {
  return tdo_vec3{std::fmin(std::fmax(p.x, b.min.x), b.max.x),
                  std::fmin(std::fmax(p.y, b.min.y), b.max.y),
                  std::fmin(std::fmax(p.z, b.min.z), b.max.z)};
}

/** Independent model: does the segment p -> q pass through the open interior of b? Sampled
 *  densely (2000 points strictly between the ends), a point counts when it is at least 1e-7 m
 *  inside every face. */
bool model_blocks(const tdo_box& b, tdo_vec3 p, tdo_vec3 q) {
  for (int k = 1; k < 2000; ++k) {
    const double s = k / 2000.0;
    const tdo_vec3 x{p.x + (q.x - p.x) * s, p.y + (q.y - p.y) * s, p.z + (q.z - p.z) * s};
    const double e = 1e-7;
    if (x.x > b.min.x + e && x.x < b.max.x - e && x.y > b.min.y + e && x.y < b.max.y - e &&
        x.z > b.min.z + e && x.z < b.max.z - e)
      return true;
  }
  return false;
}

/** Independent model: some point of box i on a fine 41 x 41 lattice of its faces (or its closest
 *  point) is within range and not behind another box. */
bool model_visible(const std::vector<tdo_box>& boxes, size_t i, tdo_vec3 p, double range) {
  const tdo_box& b = boxes[i];
  std::vector<tdo_vec3> pts{closest(b, p)};
  const int g = 40;
  for (int face = 0; face < 6; ++face) {
    for (int u = 0; u <= g; ++u) {
      for (int w = 0; w <= g; ++w) {
        const double fu = static_cast<double>(u) / g, fw = static_cast<double>(w) / g;
        const double lo[3] = {b.min.x, b.min.y, b.min.z}, hi[3] = {b.max.x, b.max.y, b.max.z};
        double c[3];
        const int a = face / 2;
        c[a] = face % 2 ? hi[a] : lo[a];
        c[(a + 1) % 3] = lo[(a + 1) % 3] + (hi[(a + 1) % 3] - lo[(a + 1) % 3]) * fu;
        c[(a + 2) % 3] = lo[(a + 2) % 3] + (hi[(a + 2) % 3] - lo[(a + 2) % 3]) * fw;
        pts.push_back(tdo_vec3{c[0], c[1], c[2]});
      }
    }
  }
  for (const tdo_vec3& q : pts) {
    if (dist3(p, q) > range) continue;
    bool blocked = false;
    for (size_t j = 0; j < boxes.size() && !blocked; ++j)
      blocked = dist3(closest(boxes[j], p), p) < dist3(p, q) && model_blocks(boxes[j], p, q);
    // Its own interior too: a far face point seen through the box itself does not count.
    if (!blocked) return true;
  }
  return false;
}

struct Sensor {
  std::vector<tdo_box> boxes;
  std::vector<uint8_t> known;
  std::vector<uint32_t> revealed;
  explicit Sensor(std::vector<tdo_box> b, uint32_t cap = 64u)
      : boxes(std::move(b)), known(boxes.size(), 0u), revealed(cap, 0u) {}
  tdo_status run(tdo_vec3 p, double range, tdo_sense_output* out) {
    tdo_sense_input in{};
    in.p = p;
    in.range = range;
    in.boxes = boxes.data();
    in.n_boxes = static_cast<uint32_t>(boxes.size());
    in.known = known.data();
    in.revealed = revealed.data();
    in.max_revealed = static_cast<uint32_t>(revealed.size());
    return tdo_sense_run(&in, out);
  }
};

// GIVEN a hidden box 3 m ahead in the open WHEN sensed with range 2 m THEN nothing is revealed;
// WHEN sensed with range 5 m (or after flying closer) THEN it is revealed once, listed, flagged.
TEST(Sense, RevealsWithinRangeOnce) {
  Sensor s({tdo_box{{3, -1, -1}, {4, 1, 1}}});
  tdo_sense_output o{};
  ASSERT_EQ(s.run({0, 0, 0}, 2.0, &o), TDO_OK);
  EXPECT_EQ(o.n_revealed, 0u);
  EXPECT_EQ(o.hidden_left, 1u);
  EXPECT_EQ(s.known[0], 0u);
  ASSERT_EQ(s.run({1.5, 0, 0}, 2.0, &o), TDO_OK);
  ASSERT_EQ(o.n_revealed, 1u);
  EXPECT_EQ(s.revealed[0], 0u);
  EXPECT_EQ(s.known[0], 1u);
  EXPECT_EQ(o.hidden_left, 0u);
  ASSERT_EQ(s.run({1.5, 0, 0}, 2.0, &o), TDO_OK);
  EXPECT_EQ(o.n_revealed, 0u) << "a known box is not revealed again";
}

// GIVEN a small box behind a wall (both hidden, both within range) WHEN sensed THEN only the wall
// is revealed; GIVEN a box that reaches out beside the wall THEN it is seen past the wall's edge.
TEST(Sense, WallOccludesWhatIsBehindIt) {
  const tdo_box wall{{1.0, -1.0, -1.0}, {1.2, 1.0, 1.0}};
  const tdo_box hidden{{3.0, -0.5, -0.5}, {3.5, 0.5, 0.5}};
  const tdo_box beside{{3.0, 0.5, -0.5}, {3.5, 4.5, 0.5}};
  Sensor s({wall, hidden, beside});
  tdo_sense_output o{};
  ASSERT_EQ(s.run({0, 0, 0}, 6.0, &o), TDO_OK);
  EXPECT_EQ(s.known[0], 1u);
  EXPECT_EQ(s.known[1], 0u) << "the box behind the wall must stay hidden";
  EXPECT_EQ(s.known[2], 1u) << "the box reaching out beside the wall is visible past its edge";
  // The independent model agrees on all three.
  for (size_t i = 0; i < 3; ++i)
    EXPECT_EQ(model_visible(s.boxes, i, {0, 0, 0}, 6.0), s.known[i] != 0u) << "box " << i;
  // Flying round the wall reveals the hidden box.
  ASSERT_EQ(s.run({2.0, 2.0, 0.0}, 6.0, &o), TDO_OK);
  EXPECT_EQ(s.known[1], 1u);
}

// GIVEN 300 random boxes and 200 random sensor positions WHEN sensed from scratch THEN (a) every
// revealed box is visible in the independent fine-lattice model (never revealed early), (b) the
// box nearest to the sensor is always revealed when within range, and (c) no box out of range is.
TEST(Sense, NearestBoxIsAlwaysSeenAndNothingEarly) {
  tdo_test::Rng rng(20);
  std::vector<tdo_box> boxes;
  for (int i = 0; i < 300; ++i) {
    const double x = rng.uniform(0, 30), y = rng.uniform(0, 30), z = rng.uniform(0, 8);
    boxes.push_back(
        tdo_box{{x, y, z},
                {x + rng.uniform(0.2, 1.5), y + rng.uniform(0.2, 1.5), z + rng.uniform(0.2, 4.0)}});
  }
  int nearest_checked = 0, revealed_total = 0;
  for (int trial = 0; trial < 200; ++trial) {
    const tdo_vec3 p{rng.uniform(0, 30), rng.uniform(0, 30), rng.uniform(0, 10)};
    const double range = rng.uniform(1.0, 6.0);
    Sensor s(boxes, 400u);
    tdo_sense_output o{};
    ASSERT_EQ(s.run(p, range, &o), TDO_OK);
    size_t nearest = 0;
    for (size_t i = 0; i < boxes.size(); ++i) {
      const double d = dist3(closest(boxes[i], p), p);
      if (d < dist3(closest(boxes[nearest], p), p)) nearest = i;
      if (s.known[i]) {
        EXPECT_LE(d, range);
        if (trial < 40) {
          EXPECT_TRUE(model_visible(boxes, i, p, range)) << trial << " box " << i;
        }
      }
    }
    revealed_total += static_cast<int>(o.n_revealed);
    if (dist3(closest(boxes[nearest], p), p) <= range) {
      ++nearest_checked;
      EXPECT_EQ(s.known[nearest], 1u) << "trial " << trial;
    }
  }
  EXPECT_GT(nearest_checked, 50) << "the scenario must exercise the guarantee";
  EXPECT_GT(revealed_total, 200);
}

// GIVEN three visible boxes and room for two WHEN sensed THEN the status names the full buffer,
// the first two by index are revealed and the third on the next call.
TEST(Sense, FullBufferIsNamedAndNothingIsLost) {
  Sensor s({tdo_box{{2, -4, -1}, {3, -3, 1}}, tdo_box{{2, -0.5, -1}, {3, 0.5, 1}},
            tdo_box{{2, 3, -1}, {3, 4, 1}}},
           2u);
  tdo_sense_output o{};
  EXPECT_EQ(s.run({0, 0, 0}, 10.0, &o), TDO_ERR_BOX_CAPACITY);
  ASSERT_EQ(o.n_revealed, 2u);
  EXPECT_EQ(s.revealed[0], 0u);
  EXPECT_EQ(s.revealed[1], 1u);
  EXPECT_EQ(s.known[2], 0u);
  EXPECT_EQ(o.hidden_left, 1u);
  EXPECT_EQ(s.run({0, 0, 0}, 10.0, &o), TDO_OK);
  ASSERT_EQ(o.n_revealed, 1u);
  EXPECT_EQ(s.revealed[0], 2u);
}

// GIVEN a sensor inside a box THEN the box is revealed (distance 0).
TEST(Sense, SensorInsideABoxRevealsIt) {
  Sensor s({tdo_box{{-1, -1, -1}, {1, 1, 1}}});
  tdo_sense_output o{};
  ASSERT_EQ(s.run({0, 0, 0}, 0.5, &o), TDO_OK);
  EXPECT_EQ(o.n_revealed, 1u);
}

TEST(Sense, BadInputIsNamed) {
  Sensor s({tdo_box{{2, -1, -1}, {3, 1, 1}}});
  tdo_sense_output o{};
  EXPECT_EQ(tdo_sense_run(nullptr, &o), TDO_ERR_INVALID_ARGUMENT);
  EXPECT_EQ(s.run({std::nan(""), 0, 0}, 5.0, &o), TDO_ERR_INVALID_ARGUMENT);
  EXPECT_EQ(s.run({0, 0, 0}, 0.0, &o), TDO_ERR_INVALID_ARGUMENT);
  EXPECT_EQ(s.run({0, 0, 0}, HUGE_VAL, &o), TDO_ERR_INVALID_ARGUMENT);
  s.boxes[0].max.x = 2.0;  // max <= min
  EXPECT_EQ(s.run({0, 0, 0}, 5.0, &o), TDO_ERR_INVALID_BOX);
  EXPECT_EQ(s.known[0], 0u);
  tdo_sense_input in{};
  in.p = tdo_vec3{0, 0, 0};
  in.range = 1.0;
  in.n_boxes = 1u;  // boxes null
  EXPECT_EQ(tdo_sense_run(&in, &o), TDO_ERR_INVALID_ARGUMENT);
}

// GIVEN a grid without a box and the sensor's update of a revealed box WHEN applied with
// tdo_grid_apply_update THEN the grid's collision queries see the box; bad indices and a small
// buffer are named.
TEST(Sense, UpdateAddsTheRevealedBoxesToAGrid) {
  TestPlanner tp(tdo_test::make_cap(20u * 20u * 6u, 1000u, 100u, 8u));
  ASSERT_EQ(tp.status(), TDO_OK);
  const tdo_grid_desc d{20, 20, 6, 1.0, tdo_vec3{0.0, 0.0, 0.0}};
  ASSERT_EQ(tdo_grid_reset(tp.grid(), &d), TDO_OK);
  ASSERT_EQ(tdo_grid_finish(tp.grid(), 0.5), TDO_OK);
  const std::vector<tdo_box> world{tdo_box{{15, 15, 0}, {16, 16, 6}},
                                   tdo_box{{8, 9, 0}, {9, 11, 6}}};
  Sensor s(world);
  tdo_sense_output o{};
  ASSERT_EQ(s.run({5.0, 10.0, 3.0}, 4.0, &o), TDO_OK);
  ASSERT_EQ(o.n_revealed, 1u);
  EXPECT_EQ(s.revealed[0], 1u);
  tdo_box buf[4];
  tdo_grid_update up{};
  EXPECT_EQ(tdo_sense_update(world.data(), 2u, s.revealed.data(), 1u, buf, 0u, &up),
            TDO_ERR_BOX_CAPACITY);
  const uint32_t bad = 2u;
  EXPECT_EQ(tdo_sense_update(world.data(), 2u, &bad, 1u, buf, 4u, &up), TDO_ERR_INVALID_ARGUMENT);
  ASSERT_EQ(tdo_sense_update(world.data(), 2u, s.revealed.data(), 1u, buf, 4u, &up), TDO_OK);
  EXPECT_EQ(up.n_boxes, 1u);
  EXPECT_EQ(up.n_set + up.n_clear, 0u);
  EXPECT_GT(tdo_collision_point_distance(tp.grid(), {7.5, 10.0, 3.0}, 5.0), 1.4);
  tdo_grid_update_result r{};
  ASSERT_EQ(tdo_grid_apply_update(tp.grid(), &up, &r), TDO_OK);
  EXPECT_EQ(r.boxes_added, 1u);
  EXPECT_NEAR(tdo_collision_point_distance(tp.grid(), {7.5, 10.0, 3.0}, 5.0), 0.5, 1e-12);
  tdo_voxel v{};
  ASSERT_TRUE(tdo_grid_world_to_voxel(tp.grid(), {8.5, 10.0, 3.0}, &v));
  EXPECT_TRUE(tdo_grid_is_blocked(tp.grid(), v));
}

// ---- The seeded choice of hidden boxes (tdo_sense_hide) ----

std::vector<uint8_t> hide(uint32_t n, double f, uint64_t seed) {
  std::vector<uint8_t> known(n, 7u);
  EXPECT_EQ(tdo_sense_hide(n, f, seed, known.data()), TDO_OK);
  return known;
}

uint32_t hidden_count(const std::vector<uint8_t>& known) {
  uint32_t h = 0;
  for (uint8_t k : known) {
    EXPECT_TRUE(k == 0u || k == 1u);
    h += k == 0u;
  }
  return h;
}

// GIVEN box counts and fractions (ties at .5 included) WHEN boxes are hidden THEN exactly
// floor(F n + 0.5) are hidden and every flag is 0 or 1.
TEST(SenseHide, HidesExactlyTheDocumentedCount) {
  const uint32_t ns[] = {0u, 1u, 2u, 3u, 7u, 10u, 100u, 300u, 1001u};
  const double fs[] = {0.0, 0.1, 0.25, 0.3, 1.0 / 3.0, 0.5, 0.75, 0.999, 1.0};
  for (uint32_t n : ns) {
    for (double f : fs) {
      const auto want = static_cast<uint32_t>(std::floor(f * n + 0.5));
      for (uint64_t seed = 1; seed <= 5; ++seed)
        EXPECT_EQ(hidden_count(hide(n, f, seed)), want) << "n " << n << " f " << f;
    }
  }
  EXPECT_EQ(hidden_count(hide(3u, 0.5, 9u)), 2u);  // 1.5 rounds up
  EXPECT_EQ(hidden_count(hide(1u, 0.5, 9u)), 1u);  // 0.5 rounds up
  EXPECT_EQ(hidden_count(hide(300u, 1.0, 9u)), 300u);
}

// GIVEN one seed THEN the same boxes every call; GIVEN 50 seeds THEN 50 different sets.
TEST(SenseHide, DeterministicAndSeedsDiffer) {
  EXPECT_EQ(hide(300u, 0.3, 1001u), hide(300u, 0.3, 1001u));
  std::vector<std::vector<uint8_t>> sets;
  for (uint64_t seed = 1; seed <= 50; ++seed) sets.push_back(hide(300u, 0.3, seed));
  for (size_t a = 0; a < sets.size(); ++a)
    for (size_t b = a + 1; b < sets.size(); ++b) EXPECT_NE(sets[a], sets[b]) << a << " " << b;
}

// GIVEN 4000 seeds, 10 boxes, F = 0.3 THEN every box is hidden in about 30 % of them (binomial
// standard deviation 29 of 1200; 5 deviations allowed): no position is favoured.
TEST(SenseHide, EveryBoxIsEquallyLikely) {
  uint32_t times[10] = {};
  for (uint64_t seed = 0; seed < 4000u; ++seed) {
    const std::vector<uint8_t> k = hide(10u, 0.3, seed);
    for (int i = 0; i < 10; ++i) times[i] += k[static_cast<size_t>(i)] == 0u;
  }
  for (int i = 0; i < 10; ++i) EXPECT_NEAR(times[i], 1200.0, 145.0) << "box " << i;
}

// GIVEN a fraction that is NaN, infinite or outside [0, 1], or no output THEN invalid_argument
// and the flags untouched.
TEST(SenseHide, BadInputIsRefusedByName) {
  std::vector<uint8_t> known(5u, 7u);
  const double bad[] = {std::nan(""), -0.01, 1.01, HUGE_VAL, -HUGE_VAL};
  for (double f : bad) {
    EXPECT_EQ(tdo_sense_hide(5u, f, 1u, known.data()), TDO_ERR_INVALID_ARGUMENT) << f;
    EXPECT_EQ(known, std::vector<uint8_t>(5u, 7u));
  }
  EXPECT_EQ(tdo_sense_hide(5u, 0.5, 1u, nullptr), TDO_ERR_INVALID_ARGUMENT);
  EXPECT_EQ(tdo_sense_hide(0u, 0.5, 1u, nullptr), TDO_OK);
  EXPECT_STREQ(tdo_status_str(TDO_ERR_INVALID_ARGUMENT), "invalid_argument");
}

// ---- The true world's contact distance (tdo_sense_distance) ----

// Reference: per axis the gap outside the box (0 inside), then the Euclidean norm of the gaps;
// the smallest over every box.
double reference_distance(const std::vector<tdo_box>& boxes, tdo_vec3 p) {
  double best = HUGE_VAL;
  for (const tdo_box& b : boxes) {
    const double gx = std::fmax(0.0, std::fmax(b.min.x - p.x, p.x - b.max.x));
    const double gy = std::fmax(0.0, std::fmax(b.min.y - p.y, p.y - b.max.y));
    const double gz = std::fmax(0.0, std::fmax(b.min.z - p.z, p.z - b.max.z));
    best = std::fmin(best, std::hypot(gx, std::hypot(gy, gz)));
  }
  return best;
}

// GIVEN 200 random worlds of 1-40 boxes and 50 random points each (some inside, some on faces)
// WHEN the distance is asked THEN it equals the brute-force reference to 1e-12 m.
TEST(SenseDistance, MatchesBruteForceOnRandomBoxes) {
  tdo_test::Rng rng(20u);
  int inside = 0, on_face = 0;
  for (int w = 0; w < 200; ++w) {
    std::vector<tdo_box> boxes(1u + rng.below(40u));
    for (tdo_box& b : boxes) {
      b.min = tdo_vec3{rng.uniform(0, 20), rng.uniform(0, 20), rng.uniform(0, 10)};
      b.max = tdo_vec3{b.min.x + rng.uniform(0.1, 4), b.min.y + rng.uniform(0.1, 4),
                       b.min.z + rng.uniform(0.1, 4)};
    }
    for (int k = 0; k < 50; ++k) {
      tdo_vec3 p{rng.uniform(-3, 27), rng.uniform(-3, 27), rng.uniform(-3, 17)};
      if (k % 10 == 0) {  // on a face of a box
        const tdo_box& b = boxes[rng.below(static_cast<uint32_t>(boxes.size()))];
        p = tdo_vec3{rng.uniform(b.min.x, b.max.x), rng.uniform(b.min.y, b.max.y), b.max.z};
      }
      double d = -1.0;
      ASSERT_EQ(tdo_sense_distance(boxes.data(), static_cast<uint32_t>(boxes.size()), p, &d),
                TDO_OK);
      const double want = reference_distance(boxes, p);
      EXPECT_NEAR(d, want, 1e-12);
      inside += !(want > 0.0);
      on_face += k % 10 == 0;
      EXPECT_EQ(d > 0.0, want > 0.0);
    }
  }
  EXPECT_GT(inside, 1000);  // the worlds are dense enough to test inside points
  EXPECT_EQ(on_face, 1000);
}

TEST(SenseDistance, EdgeCasesAndBadInputAreNamed) {
  const std::vector<tdo_box> boxes{tdo_box{{0, 0, 0}, {1, 1, 1}}};
  double d = 0.0;
  ASSERT_EQ(tdo_sense_distance(boxes.data(), 1u, {4.0, 5.0, 1.0}, &d), TDO_OK);
  EXPECT_DOUBLE_EQ(d, 5.0);  // 3-4-5 from the edge x = 1, y = 1
  ASSERT_EQ(tdo_sense_distance(nullptr, 0u, {0, 0, 0}, &d), TDO_OK);
  EXPECT_EQ(d, HUGE_VAL);
  EXPECT_EQ(tdo_sense_distance(boxes.data(), 1u, {std::nan(""), 0, 0}, &d),
            TDO_ERR_INVALID_ARGUMENT);
  EXPECT_EQ(tdo_sense_distance(nullptr, 1u, {0, 0, 0}, &d), TDO_ERR_INVALID_ARGUMENT);
  EXPECT_EQ(tdo_sense_distance(boxes.data(), 1u, {0, 0, 0}, nullptr), TDO_ERR_INVALID_ARGUMENT);
  const std::vector<tdo_box> bad{tdo_box{{0, 0, 0}, {1, 1, 1}}, tdo_box{{0, 2, 0}, {1, 1, 1}}};
  EXPECT_EQ(tdo_sense_distance(bad.data(), 2u, {5, 5, 5}, &d), TDO_ERR_INVALID_BOX);
  EXPECT_EQ(d, HUGE_VAL);
}

}  // namespace
