// The correction's segment checks (collision_internal.h: segment_clear_steered, block_clear)
// against the exact queries of collision.h on the repository's maps
// (maps/map1-5.tdomap: boxes; maps/movingai Simple and Complex: voxel cubes): the same answer on
// every segment, also on segments that graze obstacles at exactly the clearance, pass a hair's
// breadth either side of it, or join voxel centres the way the correction's chords do.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "../../libtdo/src/collision_internal.h"
#include "rng.h"
#include "tdo/collision.h"
#include "test_util.h"

namespace {

using tdo_test::Rng;
using tdo_test::TestPlanner;

// A map as the repository stores it: its grid, its boxes and its voxel cubes.
struct MapFile {
  tdo_grid_desc desc{};
  std::vector<tdo_box> boxes;
  std::vector<tdo_voxel> cubes;
};

std::string map_path(const std::string& name) {
  return std::string(TDO_SOURCE_DIR) + "/maps/" + name;
}

// .tdomap: 'bounds', 'resolution' and 'box' lines (docs/map_format.md); the rest is not needed.
bool read_tdomap(const std::string& path, MapFile* m) {
  std::ifstream in(path);
  if (!in) return false;
  double lo[3] = {0, 0, 0}, hi[3] = {0, 0, 0}, res = 0.0;
  std::string line;
  while (std::getline(in, line)) {
    std::istringstream ls(line);
    std::string kw;
    if (!(ls >> kw) || kw[0] == '#') continue;
    if (kw == "bounds") {
      ls >> lo[0] >> lo[1] >> lo[2] >> hi[0] >> hi[1] >> hi[2];
    } else if (kw == "resolution") {
      ls >> res;
    } else if (kw == "box") {
      tdo_box b{};
      ls >> b.min.x >> b.min.y >> b.min.z >> b.max.x >> b.max.y >> b.max.z;
      m->boxes.push_back(b);
    }
  }
  if (!(res > 0.0)) return false;
  int32_t n[3];
  for (int a = 0; a < 3; ++a)
    n[a] = std::max(1, static_cast<int32_t>(std::ceil((hi[a] - lo[a]) / res - 1e-9)));
  m->desc = tdo_grid_desc{n[0], n[1], n[2], res, tdo_vec3{lo[0], lo[1], lo[2]}};
  return true;
}

// MovingAI .3dmap: 'voxel X Y Z' then one occupied voxel per line; voxel centres at integers.
bool read_3dmap(const std::string& path, MapFile* m) {
  std::ifstream in(path);
  std::string kw;
  int32_t n[3];
  if (!(in >> kw >> n[0] >> n[1] >> n[2]) || kw != "voxel") return false;
  m->desc = tdo_grid_desc{n[0], n[1], n[2], 1.0, tdo_vec3{-0.5, -0.5, -0.5}};
  int32_t x, y, z;
  while (in >> x >> y >> z) m->cubes.push_back(tdo_voxel{x, y, z});
  return !m->cubes.empty();
}

bool read_map(const std::string& name, MapFile* m) {
  const std::string path = map_path(name);
  return name.size() > 6 && name.substr(name.size() - 6) == ".3dmap" ? read_3dmap(path, m)
                                                                     : read_tdomap(path, m);
}

// A planner holding one map, finished at `finish_c`.
class MapGrid {
 public:
  explicit MapGrid(const MapFile& m)
      : pl_(tdo_test::make_cap(static_cast<uint32_t>(m.desc.nx) * static_cast<uint32_t>(m.desc.ny) *
                                   static_cast<uint32_t>(m.desc.nz),
                               1000u, 1000u, static_cast<uint32_t>(m.boxes.size()) + 1u, 200000u)),
        map_(m) {}
  tdo_status load(double finish_c) {
    if (pl_.status() != TDO_OK) return pl_.status();
    return tdo_test::load_grid(grid(), map_.desc, map_.boxes, finish_c, map_.cubes);
  }
  tdo_grid* grid() { return pl_.grid(); }

 private:
  TestPlanner pl_;
  const MapFile& map_;
};

// Segments that exercise the checks on one map: long and short random ones, chords between voxel
// centres (the correction's input points and their shortcuts), and near misses of obstacles.
class SegmentMaker {
 public:
  SegmentMaker(const MapFile& m, uint64_t seed) : m_(m), rng_(seed) {
    for (const tdo_box& b : m.boxes) solids_.push_back(b);
    const double r = m.desc.res;
    const tdo_vec3 o = m.desc.origin;
    for (const tdo_voxel& v : m.cubes)
      solids_.push_back(
          tdo_box{tdo_vec3{o.x + v.i * r, o.y + v.j * r, o.z + v.k * r},
                  tdo_vec3{o.x + (v.i + 1) * r, o.y + (v.j + 1) * r, o.z + (v.k + 1) * r}});
  }

  // Kind k of segment (0 .. kKinds - 1) at clearance c; false when it leaves the bounds.
  static constexpr int kKinds = 6;
  bool make(int kind, double c, tdo_vec3* a, tdo_vec3* b) {
    switch (kind) {
      case 0:  // anywhere
        *a = random_point();
        *b = random_point();
        break;
      case 1:  // short, near an obstacle
        *a = near_solid(3.0);
        *b = offset(*a, 3.0 * m_.desc.res);
        break;
      case 2:  // voxel centre to voxel centre, a few voxels apart (the correction's chords)
        *a = centre_near_solid();
        *b = add(*a, scaled(tdo_vec3{static_cast<double>(rng_.range(-6, 6)),
                                     static_cast<double>(rng_.range(-6, 6)),
                                     static_cast<double>(rng_.range(-3, 3))},
                            m_.desc.res));
        break;
      case 3:  // grazing: parallel to a face of an obstacle at exactly c (or a hair inside/outside)
        graze(c, a, b);
        break;
      case 4:  // through a corner point or edge of an obstacle grown by c, along a random line
        through_corner(c, a, b);
        break;
      default:  // from a voxel centre to a point of another segment (shortcut end points)
        *a = centre_near_solid();
        *b = offset(*a, 8.0 * m_.desc.res);
        {
          const tdo_vec3 e = offset(*b, 4.0 * m_.desc.res);
          const double t = rng_.uniform();
          *b = tdo_vec3{b->x + t * (e.x - b->x), b->y + t * (e.y - b->y), b->z + t * (e.z - b->z)};
        }
        break;
    }
    return inside(*a) && inside(*b);
  }

  // A random point within `reach` (per axis) of p.
  tdo_vec3 near(const tdo_vec3& p, double reach) { return offset(p, reach); }
  bool inside(const tdo_vec3& p) const {
    const tdo_grid_desc& d = m_.desc;
    return p.x >= d.origin.x && p.y >= d.origin.y && p.z >= d.origin.z &&
           p.x <= d.origin.x + d.nx * d.res && p.y <= d.origin.y + d.ny * d.res &&
           p.z <= d.origin.z + d.nz * d.res;
  }

 private:
  static tdo_vec3 add(const tdo_vec3& p, const tdo_vec3& q) {
    return tdo_vec3{p.x + q.x, p.y + q.y, p.z + q.z};
  }
  static tdo_vec3 scaled(const tdo_vec3& p, double s) {
    return tdo_vec3{p.x * s, p.y * s, p.z * s};
  }
  tdo_vec3 random_point() {
    const tdo_grid_desc& d = m_.desc;
    return tdo_vec3{d.origin.x + rng_.uniform() * d.nx * d.res,
                    d.origin.y + rng_.uniform() * d.ny * d.res,
                    d.origin.z + rng_.uniform() * d.nz * d.res};
  }
  tdo_vec3 offset(const tdo_vec3& p, double reach) {
    return tdo_vec3{p.x + rng_.uniform(-reach, reach), p.y + rng_.uniform(-reach, reach),
                    p.z + rng_.uniform(-reach, reach)};
  }
  const tdo_box& solid() { return solids_[rng_.below(static_cast<uint32_t>(solids_.size()))]; }
  tdo_vec3 near_solid(double voxels) {
    const tdo_box& s = solid();
    const double g = voxels * m_.desc.res;
    return tdo_vec3{rng_.uniform(s.min.x - g, s.max.x + g), rng_.uniform(s.min.y - g, s.max.y + g),
                    rng_.uniform(s.min.z - g, s.max.z + g)};
  }
  tdo_vec3 centre_near_solid() {
    const tdo_vec3 p = near_solid(3.0);
    const tdo_grid_desc& d = m_.desc;
    const auto centre = [&](double x, double o) {
      return o + (std::floor((x - o) / d.res) + 0.5) * d.res;
    };
    return tdo_vec3{centre(p.x, d.origin.x), centre(p.y, d.origin.y), centre(p.z, d.origin.z)};
  }
  // A hair: 0, or a small step either way (1e-12 .. 1e-6 m).
  double hair() {
    const uint32_t k = rng_.below(5);
    if (k == 0) return 0.0;
    const double h = std::pow(10.0, -static_cast<double>(6 + 2 * (k / 2)));  // 1e-6, 1e-8, 1e-10
    return (k % 2 == 0) ? h : -h;
  }
  void graze(double c, tdo_vec3* a, tdo_vec3* b) {
    const tdo_box& s = solid();
    const double lo[3] = {s.min.x, s.min.y, s.min.z}, hi[3] = {s.max.x, s.max.y, s.max.z};
    const int axis = static_cast<int>(rng_.below(3));                    // the face's normal
    const int along = (axis + 1 + static_cast<int>(rng_.below(2))) % 3;  // the segment's direction
    double p[3], q[3];
    for (int i = 0; i < 3; ++i) p[i] = q[i] = rng_.uniform(lo[i], hi[i]);
    const bool up = rng_.below(2) == 0u;
    p[axis] = q[axis] = (up ? hi[axis] + c : lo[axis] - c) + hair();
    const double ext = 2.0 * m_.desc.res;
    p[along] = lo[along] - rng_.uniform(0.0, ext);
    q[along] = hi[along] + rng_.uniform(0.0, ext);
    if (rng_.below(3) == 0u) {  // along the face's edge, off the face itself: a rounded corner
      const int third = 3 - axis - along;
      p[third] = q[third] = hi[third] + hair();
    }
    *a = tdo_vec3{p[0], p[1], p[2]};
    *b = tdo_vec3{q[0], q[1], q[2]};
  }
  void through_corner(double c, tdo_vec3* a, tdo_vec3* b) {
    const tdo_box& s = solid();
    // A corner of the box, pushed out by c / sqrt(3) along its diagonal (distance c), or a
    // point on an edge pushed out by c along one face normal (distance c).
    double p[3] = {rng_.below(2) ? s.max.x : s.min.x, rng_.below(2) ? s.max.y : s.min.y,
                   rng_.below(2) ? s.max.z : s.min.z};
    const double mid[3] = {0.5 * (s.min.x + s.max.x), 0.5 * (s.min.y + s.max.y),
                           0.5 * (s.min.z + s.max.z)};
    if (rng_.below(2) == 0u) {
      for (int i = 0; i < 3; ++i) p[i] += (p[i] > mid[i] ? 1.0 : -1.0) * (c / std::sqrt(3.0));
    } else {
      const int i = static_cast<int>(rng_.below(3));
      p[i] += (p[i] > mid[i] ? 1.0 : -1.0) * (c + hair());
    }
    // A direction tangent-ish to the corner: perpendicular to the outward diagonal.
    double dir[3] = {rng_.uniform(-1.0, 1.0), rng_.uniform(-1.0, 1.0), rng_.uniform(-1.0, 1.0)};
    double out[3], dd = 0.0, od = 0.0;
    for (int i = 0; i < 3; ++i) {
      out[i] = p[i] > mid[i] ? 1.0 : -1.0;
      od += out[i] * dir[i];
      dd += out[i] * out[i];
    }
    for (int i = 0; i < 3; ++i) dir[i] -= od / dd * out[i];
    const double len = rng_.uniform(0.2, 6.0) * m_.desc.res;
    const double t = rng_.uniform(0.0, 1.0);
    *a = tdo_vec3{p[0] - t * len * dir[0], p[1] - t * len * dir[1], p[2] - t * len * dir[2]};
    *b = tdo_vec3{p[0] + (1 - t) * len * dir[0], p[1] + (1 - t) * len * dir[1],
                  p[2] + (1 - t) * len * dir[2]};
  }

  const MapFile& m_;
  Rng rng_;
  std::vector<tdo_box> solids_;
};

struct Tally {
  int segments = 0, clear = 0, blocked = 0, block_claims = 0, cube_hints = 0;
};

// One check of [a, b] at c: the steered forms (without hints, and with the hints of a run of
// queries) against the exact query and its hinted form.
struct Checker {
  tdo_grid* grid;
  double c;
  uint32_t hint_exact = 0u, hint_steered = 0u, cube_hint = 0u;
  Tally t;

  void check(const tdo_vec3& a, const tdo_vec3& b, int kind) {
    ++t.segments;
    const int exact = tdo_collision_segment_clear(grid, a, b, c);
    (exact == 1 ? t.clear : t.blocked) += 1;
    EXPECT_EQ(tdo_internal::segment_clear_steered(grid, a, b, c, nullptr, nullptr), exact)
        << "kind " << kind << " c " << c << " a (" << a.x << ", " << a.y << ", " << a.z << ") b ("
        << b.x << ", " << b.y << ", " << b.z << ")";
    // The hinted forms, in one run of queries each: the same answers and the same box hints.
    const int hinted = tdo_internal::segment_clear_hinted(grid, a, b, c, &hint_exact);
    EXPECT_EQ(tdo_internal::segment_clear_steered(grid, a, b, c, &hint_steered, &cube_hint), hinted)
        << "kind " << kind << " c " << c;
    EXPECT_EQ(hint_steered, hint_exact);
    EXPECT_EQ(hinted, exact);
    if (exact == 0 && cube_hint != 0u) ++t.cube_hints;
    const int block = tdo_internal::block_clear(grid, a, b, c);
    if (block == 1) {
      ++t.block_claims;
      EXPECT_EQ(exact, 1) << "block_clear claims a blocked segment clear, kind " << kind;
    }
  }
};

// Every check against the exact query on `count` segments of every kind at clearance c; every
// third segment also as a fan of chords from its start to points along a segment near its end
// (the correction's partial shortcuts, which the cube hint serves).
Tally compare(tdo_grid* grid, const MapFile& m, double c, int count, uint64_t seed) {
  SegmentMaker make(m, seed);
  Checker ck{grid, c, 0u, 0u, 0u, Tally{}};
  constexpr double kFanT[6] = {0.9375, 0.875, 0.75, 0.5, 0.25, 0.125};
  for (int n = 0; n < count; ++n) {
    tdo_vec3 a, b;
    const int kind = n % SegmentMaker::kKinds;
    if (!make.make(kind, c, &a, &b)) continue;
    ck.check(a, b, kind);
    if (n % 3 != 0) continue;
    const tdo_vec3 e = make.near(b, 2.0 * m.desc.res);
    for (double f : kFanT) {
      const tdo_vec3 p{b.x + f * (e.x - b.x), b.y + f * (e.y - b.y), b.z + f * (e.z - b.z)};
      if (make.inside(p)) ck.check(a, p, 100 + kind);
    }
  }
  return ck.t;
}

struct MapCase {
  const char* name;
  double clearances[3];
  int count;
};

class CorrectChecks : public ::testing::TestWithParam<MapCase> {};

TEST_P(CorrectChecks, SameAnswersAsTheExactQueries) {
  const MapCase mc = GetParam();
  MapFile m;
  ASSERT_TRUE(read_map(mc.name, &m)) << map_path(mc.name);
  MapGrid mg(m);
  uint64_t seed = 19;
  for (double c : mc.clearances) {
    // The grid finished at the clearance checked (the planner's case), and at 0 (a query's
    // clearance above the grid's).
    for (double finish_c : {c, 0.0}) {
      ASSERT_EQ(mg.load(finish_c), TDO_OK) << mc.name << " c " << c;
      const Tally t = compare(mg.grid(), m, c, mc.count, seed++);
      // The mix must hold both answers, and the block test must make claims.
      EXPECT_GT(t.segments, mc.count / 2) << mc.name;
      EXPECT_GE(t.clear, 50) << mc.name << " c " << c;
      EXPECT_GE(t.blocked, 50) << mc.name << " c " << c;
      EXPECT_GT(t.block_claims, 0) << mc.name << " c " << c;
      // On voxel maps the cube hint is set by the failures (box maps have none).
      if (!m.cubes.empty()) {
        EXPECT_GT(t.cube_hints, 0) << mc.name << " c " << c;
      }
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Maps, CorrectChecks,
                         ::testing::Values(MapCase{"map1.tdomap", {0.5, 0.0, 0.8}, 8000},
                                           MapCase{"map2.tdomap", {0.5, 0.0, 0.8}, 8000},
                                           MapCase{"map3.tdomap", {0.5, 0.0, 0.8}, 8000},
                                           MapCase{"map4.tdomap", {0.5, 0.0, 0.8}, 8000},
                                           MapCase{"map5.tdomap", {0.5, 0.0, 0.8}, 8000},
                                           MapCase{"movingai/Simple.3dmap", {0.0, 0.5, 0.3}, 12000},
                                           MapCase{
                                               "movingai/Complex.3dmap", {0.0, 0.5, 0.3}, 12000}),
                         [](const ::testing::TestParamInfo<MapCase>& p) {
                           std::string s = p.param.name;
                           const size_t slash = s.find('/');
                           if (slash != std::string::npos) s = s.substr(slash + 1);
                           return s.substr(0, s.find('.'));
                         });

// A voxel map built here, cube by cube, with the grid's own lattice offset away from 0 and a
// fine resolution, so that rounding differs from the integer maps above.
TEST(CorrectChecks, FineResolutionOffsetGrid) {
  MapFile m;
  m.desc = tdo_grid_desc{40, 36, 24, 0.15, tdo_vec3{-3.3, 1.7, 0.05}};
  Rng rng(7);
  for (int n = 0; n < 400; ++n)
    m.cubes.push_back(tdo_voxel{rng.range(0, 39), rng.range(0, 35), rng.range(0, 23)});
  for (int n = 0; n < 6; ++n) {  // walls
    const int32_t x = rng.range(2, 37);
    for (int32_t j = 0; j < 30; ++j)
      for (int32_t k = 0; k < 20; ++k) m.cubes.push_back(tdo_voxel{x, j, k});
  }
  MapGrid mg(m);
  uint64_t seed = 3;
  for (double c : {0.0, 0.3, 0.15}) {
    ASSERT_EQ(mg.load(c), TDO_OK);
    const Tally t = compare(mg.grid(), m, c, 12000, seed++);
    EXPECT_GE(t.clear, 50);
    EXPECT_GE(t.blocked, 50);
    // Blocks of 2 voxels' clearance around a piece are larger than block_clear reads.
    if (c < 0.2) {
      EXPECT_GT(t.block_claims, 0);
    }
    EXPECT_GT(t.cube_hints, 0);
  }
}

// The slab walk (collision.cpp, clearances up to res / 4) on cluttered voxel maps, on the
// segments where rounding decides: lattice point to lattice point (along voxel faces and edges,
// through voxel corners), voxel centre to voxel centre (diagonals through edges and corners),
// pure diagonals, axis-parallel segments on voxel planes, and random ones; clearances 0, a hair,
// res / 10, res / 4 (the walk's limit) and res / 3 (beyond it). The steered query, without and
// with hints, must answer as the exact one, always.
TEST(CorrectChecks, LatticeSegmentsThroughVoxelCornersAtSmallClearances) {
  struct Grid {
    tdo_grid_desc desc;
    double density;
  };
  const Grid grids[3] = {{tdo_grid_desc{18, 15, 11, 1.0, tdo_vec3{-0.5, -0.5, -0.5}}, 0.12},
                         {tdo_grid_desc{16, 16, 12, 0.25, tdo_vec3{0.0, 0.0, 0.0}}, 0.08},
                         {tdo_grid_desc{17, 13, 10, 0.15, tdo_vec3{-3.3, 1.7, 0.05}}, 0.2}};
  Rng rng(2026);
  int compared = 0, clear = 0, blocked = 0;
  for (const Grid& gd : grids) {
    MapFile m;
    m.desc = gd.desc;
    for (int32_t k = 0; k < m.desc.nz; ++k)
      for (int32_t j = 0; j < m.desc.ny; ++j)
        for (int32_t i = 0; i < m.desc.nx; ++i)
          if (rng.uniform() < gd.density) m.cubes.push_back(tdo_voxel{i, j, k});
    MapGrid mg(m);
    ASSERT_EQ(mg.load(0.0), TDO_OK);
    const tdo_grid_desc& d = m.desc;
    const double r = d.res;
    // Lattice point (i, j, k) plus f voxels on every axis (f = 0: a voxel corner, 0.5: a centre).
    const auto at = [&](int32_t i, int32_t j, int32_t k, double f) {
      return tdo_vec3{d.origin.x + (i + f) * r, d.origin.y + (j + f) * r, d.origin.z + (k + f) * r};
    };
    const auto inside = [&](const tdo_vec3& p) {
      return p.x >= d.origin.x && p.y >= d.origin.y && p.z >= d.origin.z &&
             p.x <= d.origin.x + d.nx * r && p.y <= d.origin.y + d.ny * r &&
             p.z <= d.origin.z + d.nz * r;
    };
    for (double c : {0.0, 1e-9, 0.1 * r, 0.25 * r, r / 3.0}) {
      uint32_t hint = 0u, cube_hint = 0u;
      for (int n = 0; n < 6000; ++n) {
        const int32_t i = rng.range(0, d.nx), j = rng.range(0, d.ny), k = rng.range(0, d.nz);
        const int32_t di = rng.range(-6, 6), dj = rng.range(-6, 6), dk = rng.range(-4, 4);
        tdo_vec3 a, b;
        switch (n % 6) {
          case 0:  // lattice point to lattice point
            a = at(i, j, k, 0.0);
            b = at(i + di, j + dj, k + dk, 0.0);
            break;
          case 1:  // voxel centre to voxel centre
            a = at(i, j, k, 0.5);
            b = at(i + di, j + dj, k + dk, 0.5);
            break;
          case 2: {  // pure diagonal from a corner or a centre
            const double f = rng.below(2) == 0u ? 0.0 : 0.5;
            a = at(i, j, k, f);
            b = at(i + di, j + (rng.below(2) == 0u ? di : -di), k + (rng.below(2) == 0u ? di : 0),
                   f);
            break;
          }
          case 3:  // axis-parallel on a voxel face or edge
            a = at(i, j, k, 0.0);
            b = a;
            b.x += di * r;
            if (rng.below(2) == 0u) a.y += 0.5 * r, b.y += 0.5 * r;
            break;
          case 4:  // centre to lattice point
            a = at(i, j, k, 0.5);
            b = at(i + di, j + dj, k + dk, 0.0);
            break;
          default:  // random
            a = at(i, j, k, rng.uniform());
            b = at(i + di, j + dj, k + dk, rng.uniform());
            break;
        }
        if (!inside(a) || !inside(b)) continue;
        const int exact = tdo_collision_segment_clear(mg.grid(), a, b, c);
        ASSERT_EQ(tdo_internal::segment_clear_steered(mg.grid(), a, b, c, nullptr, nullptr), exact)
            << "c " << c << " kind " << n % 6 << " a (" << a.x << ", " << a.y << ", " << a.z
            << ") b (" << b.x << ", " << b.y << ", " << b.z << ")";
        ASSERT_EQ(tdo_internal::segment_clear_steered(mg.grid(), a, b, c, &hint, &cube_hint), exact)
            << "hinted, c " << c << " kind " << n % 6;
        ++compared;
        (exact == 1 ? clear : blocked) += 1;
      }
    }
  }
  EXPECT_GT(compared, 40000);
  EXPECT_GT(clear, 6000);
  EXPECT_GT(blocked, 20000);
}

#if defined(TDO_KEEP_BOUNDS)
// segment_cube_distance (the correction's tightening settles a keep with it): with one surface
// cube on the grid it is the exact distance itself, bit for bit (the same leaves, each evaluated
// the same way), capped alike; with many cubes it is never below the exact distance, and it
// refuses a voxel that is not a surface cube.
TEST(CorrectChecks, SegmentCubeDistanceIsTheExactQuerysValueForItsCube) {
  Rng rng(41);
  const tdo_grid_desc descs[2] = {tdo_grid_desc{14, 12, 9, 1.0, tdo_vec3{-0.5, -0.5, -0.5}},
                                  tdo_grid_desc{20, 16, 12, 0.15, tdo_vec3{-3.3, 1.7, 0.05}}};
  int equal = 0, below_cap = 0;
  for (const tdo_grid_desc& d : descs) {
    MapFile one;
    one.desc = d;
    const tdo_voxel v{d.nx / 2, d.ny / 2, d.nz / 2};
    one.cubes.push_back(v);
    MapGrid mg(one);
    ASSERT_EQ(mg.load(0.0), TDO_OK);
    const uint32_t idx = static_cast<uint32_t>(v.i + d.nx * (v.j + d.ny * v.k));
    const double r = d.res;
    const tdo_vec3 c{d.origin.x + (v.i + 0.5) * r, d.origin.y + (v.j + 0.5) * r,
                     d.origin.z + (v.k + 0.5) * r};
    for (int n = 0; n < 4000; ++n) {
      // End points around the cube, some on its lattice (faces, edges, corners).
      tdo_vec3 e[2];
      for (tdo_vec3& p : e) {
        const double s = n % 3 == 0 ? 4.0 : 1.5;
        p = tdo_vec3{c.x + rng.uniform(-s, s) * r, c.y + rng.uniform(-s, s) * r,
                     c.z + rng.uniform(-s, s) * r};
        if (n % 4 == 1) p.x = d.origin.x + std::round((p.x - d.origin.x) / r) * r;
      }
      const double cap = n % 2 == 0 ? 1e9 : rng.uniform(0.0, 1.5) * r;
      const double exact = tdo_collision_segment_distance(mg.grid(), e[0], e[1], cap);
      const double got = tdo_internal::segment_cube_distance(mg.grid(), e[0], e[1], idx, cap);
      ASSERT_EQ(got, exact) << "n " << n << " cap " << cap;
      ++equal;
      below_cap += got < cap ? 1 : 0;
    }
  }
  EXPECT_GT(below_cap, 2000);
  // Many cubes: an upper bound of the exact distance for every surface cube near the segment.
  MapFile m;
  m.desc = descs[1];
  for (int n = 0; n < 300; ++n)
    m.cubes.push_back(tdo_voxel{rng.range(0, 19), rng.range(0, 15), rng.range(0, 11)});
  MapGrid mg(m);
  ASSERT_EQ(mg.load(0.0), TDO_OK);
  SegmentMaker make(m, 5);
  int bounded = 0;
  for (int n = 0; n < 3000; ++n) {
    tdo_vec3 a, b;
    if (!make.make(n % SegmentMaker::kKinds, 0.0, &a, &b)) continue;
    const double exact = tdo_collision_segment_distance(mg.grid(), a, b, 1e9);
    for (const tdo_voxel& v : m.cubes) {
      const uint32_t idx = static_cast<uint32_t>(v.i + m.desc.nx * (v.j + m.desc.ny * v.k));
      const double got = tdo_internal::segment_cube_distance(mg.grid(), a, b, idx, 1e9);
      if (got < 0.0) continue;  // not a surface cube
      ASSERT_GE(got, exact) << "n " << n;
      ++bounded;
    }
  }
  EXPECT_GT(bounded, 100000);
  const uint32_t free_voxel = 0u;  // refused unless it is a surface cube
  bool occupied = false;
  for (const tdo_voxel& v : m.cubes) occupied = occupied || (v.i == 0 && v.j == 0 && v.k == 0);
  if (!occupied) {
    EXPECT_EQ(tdo_internal::segment_cube_distance(mg.grid(), tdo_vec3{0.0, 2.0, 0.1},
                                                  tdo_vec3{-3.0, 3.0, 1.0}, free_voxel, 1e9),
              -1.0);
  }
  EXPECT_EQ(equal, 8000);
}
#endif

}  // namespace
