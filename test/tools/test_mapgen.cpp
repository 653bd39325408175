// Tests of the benchmark map generator (tools/tdo-mapgen): the random numbers, the presets, the
// column and corridor layouts, the movers, and solvability checked by an independent search.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <deque>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "mapgen.h"
#include "tdo_io/map_io.h"

namespace fs = std::filesystem;
using ::testing::HasSubstr;

namespace {

class Mapgen : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::temp_directory_path() / ("tdo_mapgen_" + std::string(info->name()) + "_" +
                                        std::to_string(static_cast<long>(::getpid())));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  std::string path(const std::string& name) const { return (dir_ / name).string(); }

  /** Generate and also write the text to DIR/name so tdo_io can read it back. */
  tdo_mapgen::Result make(const tdo_mapgen::Params& p, const std::string& name) {
    tdo_mapgen::Result r;
    std::string err;
    EXPECT_TRUE(tdo_mapgen::generate(p, path(name + ".scratch"), &r, &err)) << err;
    std::ofstream(path(name), std::ios::binary) << r.text;
    return r;
  }

  fs::path dir_;
};

/** Distance from point p to the closed box b. */
double box_distance(const tdo_box& b, const tdo_vec3& p) {
  const double dx = std::max({b.min.x - p.x, 0.0, p.x - b.max.x});
  const double dy = std::max({b.min.y - p.y, 0.0, p.y - b.max.y});
  const double dz = std::max({b.min.z - p.z, 0.0, p.z - b.max.z});
  return std::sqrt(dx * dx + dy * dy + dz * dz);
}

/**
 * Independent solvability check, written from the definitions of docs/design.md s.0 without libtdo:
 * a voxel is blocked when it intersects a box interior or its centre is closer than `clearance` to
 * a box. 26-connected moves without corner cutting connect exactly the voxels that 6-connected
 * moves connect (every legal diagonal step has its whole 2x2(x2) block free), so a breadth-first
 * search over face neighbours decides reachability.
 */
bool independently_solvable(const tdo_io::Map& m, double clearance) {
  const tdo_grid_desc& d = m.desc;
  const auto n = static_cast<std::size_t>(d.nx) * d.ny * d.nz;
  std::vector<uint8_t> blocked(n, 0);
  const auto idx = [&](int i, int j, int k) {
    return (static_cast<std::size_t>(k) * d.ny + j) * d.nx + i;
  };
  for (int k = 0; k < d.nz; ++k) {
    for (int j = 0; j < d.ny; ++j) {
      for (int i = 0; i < d.nx; ++i) {
        const tdo_vec3 lo{d.origin.x + i * d.res, d.origin.y + j * d.res, d.origin.z + k * d.res};
        const tdo_vec3 c{lo.x + 0.5 * d.res, lo.y + 0.5 * d.res, lo.z + 0.5 * d.res};
        for (const tdo_box& b : m.boxes) {
          const bool hits = lo.x < b.max.x && lo.x + d.res > b.min.x && lo.y < b.max.y &&
                            lo.y + d.res > b.min.y && lo.z < b.max.z && lo.z + d.res > b.min.z;
          if (hits || box_distance(b, c) < clearance) {
            blocked[idx(i, j, k)] = 1;
            break;
          }
        }
      }
    }
  }
  const auto voxel_of = [&](const tdo_vec3& p, int v[3]) {
    v[0] = static_cast<int>(std::floor((p.x - d.origin.x) / d.res));
    v[1] = static_cast<int>(std::floor((p.y - d.origin.y) / d.res));
    v[2] = static_cast<int>(std::floor((p.z - d.origin.z) / d.res));
  };
  int s[3];
  int g[3];
  voxel_of(m.start, s);
  voxel_of(m.goal, g);
  if (blocked[idx(s[0], s[1], s[2])] != 0 || blocked[idx(g[0], g[1], g[2])] != 0) return false;
  std::vector<uint8_t> seen(n, 0);
  std::deque<std::array<int, 3>> queue{{s[0], s[1], s[2]}};
  seen[idx(s[0], s[1], s[2])] = 1;
  const int steps[6][3] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  while (!queue.empty()) {
    const auto v = queue.front();
    queue.pop_front();
    if (v[0] == g[0] && v[1] == g[1] && v[2] == g[2]) return true;
    for (const auto& st : steps) {
      const int i = v[0] + st[0];
      const int j = v[1] + st[1];
      const int k = v[2] + st[2];
      if (i < 0 || j < 0 || k < 0 || i >= d.nx || j >= d.ny || k >= d.nz) continue;
      if (seen[idx(i, j, k)] != 0 || blocked[idx(i, j, k)] != 0) continue;
      seen[idx(i, j, k)] = 1;
      queue.push_back({i, j, k});
    }
  }
  return false;
}

bool is_whole(double v) { return std::fabs(v - std::round(v)) < 1e-12; }

// ------------------------------------------------------------------------------------ random

TEST(MapgenRng, GivenSplitmix64ThenReferenceOutputs) {
  // Reference values of Vigna's splitmix64.c for the seed 1234567.
  uint64_t state = 1234567;
  EXPECT_EQ(tdo_mapgen::splitmix64(&state), 6457827717110365317ull);
  EXPECT_EQ(tdo_mapgen::splitmix64(&state), 3203168211198807973ull);
  EXPECT_EQ(tdo_mapgen::splitmix64(&state), 9817491932198370423ull);
  EXPECT_EQ(tdo_mapgen::splitmix64(&state), 4593380528125082431ull);
  EXPECT_EQ(tdo_mapgen::splitmix64(&state), 16408922859458223821ull);
}

TEST(MapgenRng, GivenSameSeedAndStreamThenSameSequenceElseDifferent) {
  tdo_mapgen::Rng a(42, 0);
  tdo_mapgen::Rng b(42, 0);
  tdo_mapgen::Rng c(42, 1);
  tdo_mapgen::Rng d(43, 0);
  int same_c = 0;
  int same_d = 0;
  for (int i = 0; i < 1000; ++i) {
    const uint64_t x = a.next();
    EXPECT_EQ(x, b.next());
    same_c += x == c.next() ? 1 : 0;
    same_d += x == d.next() ? 1 : 0;
  }
  EXPECT_EQ(same_c, 0);
  EXPECT_EQ(same_d, 0);
}

TEST(MapgenRng, GivenRangeThenEveryValueInsideAndAllHit) {
  tdo_mapgen::Rng r(7, 3);
  std::vector<int> hits(7, 0);
  for (int i = 0; i < 70000; ++i) {
    const int64_t v = r.range(-3, 3);
    ASSERT_GE(v, -3);
    ASSERT_LE(v, 3);
    ++hits[static_cast<std::size_t>(v + 3)];
  }
  for (int h : hits) EXPECT_NEAR(h, 10000, 600);  // ~6 sigma
  EXPECT_EQ(r.range(5, 5), 5);
}

TEST(MapgenText, GivenFixedPointValuesThenShortestExactDecimals) {
  EXPECT_EQ(tdo_mapgen::fixed_text(73, 1), "7.3");
  EXPECT_EQ(tdo_mapgen::fixed_text(70, 1), "7");
  EXPECT_EQ(tdo_mapgen::fixed_text(0, 4), "0");
  EXPECT_EQ(tdo_mapgen::fixed_text(-5, 3), "-0.005");
  EXPECT_EQ(tdo_mapgen::fixed_text(123450, 4), "12.345");
  EXPECT_EQ(tdo_mapgen::fixed_text(-20000, 4), "-2");
}

// ------------------------------------------------------------------------------------ presets

TEST(MapgenPreset, GivenTheSixNamesThenPaperSizesAndQueries) {
  ASSERT_EQ(tdo_mapgen::preset_names().size(), 6u);
  for (const std::string& name : tdo_mapgen::preset_names()) {
    tdo_mapgen::Params p;
    ASSERT_TRUE(tdo_mapgen::preset(name, &p)) << name;
    EXPECT_EQ(tdo_mapgen::validate(p), "") << name;
    const bool small = name == "map1" || name == "map2" || name == "map3";
    EXPECT_EQ(p.size[0], small ? 20 : 50);
    EXPECT_EQ(p.size[2], 20);
    EXPECT_EQ(p.start[0], 20000);
    EXPECT_EQ(p.goal[2], small ? 100000 : 150000);
    EXPECT_EQ(tdo_mapgen::regenerate_command(p),
              "tdo-mapgen --map " + name + " -o maps/" + name + ".tdomap");
  }
  tdo_mapgen::Params p;
  EXPECT_FALSE(tdo_mapgen::preset("map7", &p));
}

TEST(MapgenPreset, GivenBadParametersThenValidateNamesTheOption) {
  tdo_mapgen::Params p;
  ASSERT_TRUE(tdo_mapgen::preset("map2", &p));
  p.name.clear();
  auto bad = p;
  bad.size[0] = 1;
  EXPECT_THAT(tdo_mapgen::validate(bad), HasSubstr("--size"));
  bad = p;
  bad.footprint_dm[0] = 30;
  bad.footprint_dm[1] = 20;
  EXPECT_THAT(tdo_mapgen::validate(bad), HasSubstr("--footprint"));
  bad = p;
  bad.goal[0] = 250000;
  EXPECT_THAT(tdo_mapgen::validate(bad), HasSubstr("--goal"));
  bad = p;
  bad.mover_speed_mm[0] = 0;
  EXPECT_THAT(tdo_mapgen::validate(bad), HasSubstr("--mover-speed"));
}

// ------------------------------------------------------------------------------------ layouts

TEST_F(Mapgen, GivenMap2ThenColumnsFollowTheRulesAndTheTextIsReproducible) {
  tdo_mapgen::Params p;
  ASSERT_TRUE(tdo_mapgen::preset("map2", &p));
  const tdo_mapgen::Result r = make(p, "map2.tdomap");
  const tdo_mapgen::Result again = make(p, "again.tdomap");
  EXPECT_EQ(r.text, again.text);
  EXPECT_TRUE(r.check.solved);

  tdo_io::Map m;
  std::string err;
  ASSERT_TRUE(tdo_io::load_map(path("map2.tdomap"), &m, &err)) << err;
  ASSERT_EQ(m.boxes.size(), 100u);
  EXPECT_TRUE(m.has_start && m.has_goal);
  for (const tdo_box& b : m.boxes) {
    const double wx = b.max.x - b.min.x;
    const double wy = b.max.y - b.min.y;
    EXPECT_GE(wx, 1.0);
    EXPECT_LE(wx, 2.0);
    EXPECT_GE(wy, 1.0);
    EXPECT_LE(wy, 2.0);
    EXPECT_TRUE(is_whole(b.min.x) && is_whole(b.min.y) && is_whole(b.max.x) && is_whole(b.max.y));
    EXPECT_DOUBLE_EQ(b.min.z, 0.0);
    EXPECT_GE(b.max.z, 1.0);
    EXPECT_LE(b.max.z, 20.0);
    EXPECT_GE(b.min.x, 0.0);
    EXPECT_LE(b.max.x, 20.0);
    EXPECT_GE(box_distance(b, m.start), 1.5);
    EXPECT_GE(box_distance(b, m.goal), 1.5);
  }
  EXPECT_TRUE(independently_solvable(m, 0.5));
}

TEST_F(Mapgen, GivenMap4ThenWallsWithDoorsAndCorridorsSolvableEvenAtOneMetre) {
  tdo_mapgen::Params p;
  ASSERT_TRUE(tdo_mapgen::preset("map4", &p));
  make(p, "map4.tdomap");
  tdo_io::Map m;
  std::string err;
  ASSERT_TRUE(tdo_io::load_map(path("map4.tdomap"), &m, &err)) << err;
  EXPECT_EQ(m.boxes.size(), 500u);
  // Each wall y = 5, 10, ..., 45 is closed below its lintels except at exactly two doors.
  for (int w = 1; w <= 9; ++w) {
    std::vector<int> covered(50, 0);
    for (const tdo_box& b : m.boxes) {
      if (std::fabs(b.min.y - 5.0 * w) < 1e-9 && std::fabs(b.max.y - (5.0 * w + 1)) < 1e-9 &&
          b.min.z <= 0.0) {
        for (int x = static_cast<int>(b.min.x); x < static_cast<int>(b.max.x); ++x) covered[x] = 1;
      }
    }
    int gaps = 0;
    for (int x = 0; x < 50; ++x)
      gaps += (covered[x] == 0 && (x == 0 || covered[x - 1] != 0)) ? 1 : 0;
    EXPECT_EQ(gaps, 2) << "wall at y = " << 5 * w;
  }
  EXPECT_TRUE(independently_solvable(m, 0.5));
  EXPECT_TRUE(independently_solvable(m, 1.0));
}

TEST_F(Mapgen, GivenMap6ThenMap5ColumnsPlusMoversCrossingTheRouteMidCourse) {
  tdo_mapgen::Params p5;
  tdo_mapgen::Params p6;
  ASSERT_TRUE(tdo_mapgen::preset("map5", &p5));
  ASSERT_TRUE(tdo_mapgen::preset("map6", &p6));
  const tdo_mapgen::Result r5 = make(p5, "map5.tdomap");
  const tdo_mapgen::Result r6 = make(p6, "map6.tdomap");
  tdo_io::Map m5;
  tdo_io::Map m6;
  std::string err;
  ASSERT_TRUE(tdo_io::load_map(path("map5.tdomap"), &m5, &err)) << err;
  ASSERT_TRUE(tdo_io::load_map(path("map6.tdomap"), &m6, &err)) << err;
  ASSERT_EQ(m5.boxes.size(), m6.boxes.size());
  for (std::size_t i = 0; i < m5.boxes.size(); ++i) {
    EXPECT_EQ(std::memcmp(&m5.boxes[i], &m6.boxes[i], sizeof(tdo_box)), 0);
  }
  EXPECT_TRUE(m5.movers.empty());
  ASSERT_GE(m6.movers.size(), 10u);
  ASSERT_EQ(r6.movers.size(), m6.movers.size());
  const std::vector<tdo_vec3>& route = r6.check.route;
  ASSERT_GE(route.size(), 2u);
  double total = 0.0;
  for (std::size_t i = 1; i < route.size(); ++i) {
    total += std::hypot(route[i].x - route[i - 1].x, route[i].y - route[i - 1].y,
                        route[i].z - route[i - 1].z);
  }
  for (std::size_t i = 0; i < m6.movers.size(); ++i) {
    const tdo_io::Mover& mv = m6.movers[i];
    const tdo_mapgen::MoverOut& out = r6.movers[i];
    EXPECT_EQ(mv.id, static_cast<int>(i + 1));
    const double speed = std::hypot(mv.vel.x, mv.vel.y, mv.vel.z);
    EXPECT_GE(speed, 0.5 - 2e-3);
    EXPECT_LE(speed, 1.5 + 2e-3);
    EXPECT_GE(mv.radius, 0.5);
    EXPECT_LE(mv.radius, 1.0);
    // Inside the bounds at t = 0, with the whole sphere.
    EXPECT_GE(mv.pos.x - mv.radius, -1e-9);
    EXPECT_LE(mv.pos.x + mv.radius, 50.0 + 1e-9);
    EXPECT_GE(mv.pos.y - mv.radius, -1e-9);
    EXPECT_LE(mv.pos.y + mv.radius, 50.0 + 1e-9);
    // The file's position and velocity reach the crossing point at the crossing time.
    const tdo_vec3 at{mv.pos.x + mv.vel.x * out.t_cross, mv.pos.y + mv.vel.y * out.t_cross,
                      mv.pos.z + mv.vel.z * out.t_cross};
    EXPECT_NEAR(at.x, out.cross.x, 1e-6);
    EXPECT_NEAR(at.y, out.cross.y, 1e-6);
    EXPECT_NEAR(at.z, out.cross.z, 1e-6);
    // The crossing point lies on the route, in its middle 30-70 %.
    double best = 1e9;
    for (std::size_t k = 1; k < route.size(); ++k) {
      const tdo_vec3 a = route[k - 1];
      const tdo_vec3 b = route[k];
      const tdo_vec3 ab{b.x - a.x, b.y - a.y, b.z - a.z};
      const double len2 = ab.x * ab.x + ab.y * ab.y + ab.z * ab.z;
      double u = len2 > 0 ? ((out.cross.x - a.x) * ab.x + (out.cross.y - a.y) * ab.y +
                             (out.cross.z - a.z) * ab.z) /
                                len2
                          : 0.0;
      u = std::min(1.0, std::max(0.0, u));
      best = std::min(best, std::hypot(a.x + u * ab.x - out.cross.x, a.y + u * ab.y - out.cross.y,
                                       a.z + u * ab.z - out.cross.z));
    }
    EXPECT_LT(best, 1e-3);
    EXPECT_GE(out.route_arc, 0.3 * total - 1e-9);
    EXPECT_LE(out.route_arc, 0.7 * total + 1e-9);
    EXPECT_GT(out.t_cross, 0.0);
  }
  EXPECT_EQ(r5.stream, r6.stream);
}

TEST_F(Mapgen, GivenRandomSeedsThenEveryMapIsSolvableByTheIndependentSearch) {
  int redrawn = 0;
  for (uint64_t seed = 1; seed <= 25; ++seed) {
    tdo_mapgen::Params p;
    p.size[0] = 16;
    p.size[1] = 12;
    p.size[2] = 8;
    p.columns = 130;
    p.seed = seed;
    const int64_t s[3] = {20000, 20000, 30000};
    const int64_t g[3] = {140000, 100000, 40000};
    std::copy(s, s + 3, p.start);
    std::copy(g, g + 3, p.goal);
    ASSERT_EQ(tdo_mapgen::validate(p), "");
    const std::string name = "r" + std::to_string(seed) + ".tdomap";
    const tdo_mapgen::Result r = make(p, name);
    ASSERT_TRUE(r.check.solved);
    redrawn += r.stream > 0 ? 1 : 0;
    tdo_io::Map m;
    std::string err;
    ASSERT_TRUE(tdo_io::load_map(path(name), &m, &err)) << err;
    EXPECT_EQ(m.boxes.size(), 130u);
    EXPECT_TRUE(independently_solvable(m, 0.5)) << "seed " << seed;
    EXPECT_THAT(r.text, HasSubstr("--seed " + std::to_string(seed) + " "));
  }
  // 130 columns of 1-3 m on 16 x 12 m block often enough that some seeds need another draw.
  EXPECT_GT(redrawn, 0);
}

TEST_F(Mapgen, GivenAnImpossibleMapThenGenerateFailsWithAMessage) {
  tdo_mapgen::Params p;
  p.size[0] = 6;
  p.size[1] = 6;
  p.size[2] = 3;
  p.columns = 200;
  p.max_streams = 3;
  const int64_t s[3] = {10000, 10000, 10000};
  const int64_t g[3] = {50000, 50000, 20000};
  std::copy(s, s + 3, p.start);
  std::copy(g, g + 3, p.goal);
  p.footprint_dm[0] = 10;
  p.footprint_dm[1] = 10;
  tdo_mapgen::Result r;
  std::string err;
  EXPECT_FALSE(tdo_mapgen::generate(p, path("x.scratch"), &r, &err));
  EXPECT_THAT(err, HasSubstr("no solvable map in 3 draw streams"));
  EXPECT_FALSE(fs::exists(path("x.scratch")));
}

}  // namespace
