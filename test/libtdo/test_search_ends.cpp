// Start and goal of a query (docs/design.md s.1, "Search ends"): tdo_search_run and the planner's
// direct route refuse the same ends with the same status. Expected statuses come from the test's
// own geometry (half-open bounds, the centre rule of s.0 by brute force, exact point distances),
// not from the library. Each end is tried three ways: the raw search, the pipeline at depth
// SEARCH, and the pipeline at depth CORRECT, where a turn-penalised query first tries the direct
// route (the straight segment, when it keeps the clearance).
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "test_util.h"

namespace {

using tdo_test::TestPlanner;

struct World {
  tdo_grid_desc desc{};
  std::vector<tdo_box> boxes;
  tdo_vec3 start{0.0, 0.0, 0.0};
  tdo_vec3 goal{0.0, 0.0, 0.0};
};

/** The fields of a .tdomap this test needs (bounds, resolution, start, goal, boxes). */
bool read_tdomap(const std::string& path, World* w) {
  std::ifstream f(path);
  if (!f) return false;
  std::string line;
  double lo[3] = {0, 0, 0}, hi[3] = {0, 0, 0};
  while (std::getline(f, line)) {
    std::istringstream s(line);
    std::string key;
    if (!(s >> key) || key[0] == '#') continue;
    if (key == "bounds") {
      s >> lo[0] >> lo[1] >> lo[2] >> hi[0] >> hi[1] >> hi[2];
    } else if (key == "resolution") {
      s >> w->desc.res;
    } else if (key == "start") {
      s >> w->start.x >> w->start.y >> w->start.z;
    } else if (key == "goal") {
      s >> w->goal.x >> w->goal.y >> w->goal.z;
    } else if (key == "box") {
      tdo_box b{};
      s >> b.min.x >> b.min.y >> b.min.z >> b.max.x >> b.max.y >> b.max.z;
      w->boxes.push_back(b);
    }
  }
  if (!(w->desc.res > 0.0)) return false;
  w->desc.origin = tdo_vec3{lo[0], lo[1], lo[2]};
  w->desc.nx = static_cast<int32_t>(std::lround((hi[0] - lo[0]) / w->desc.res));
  w->desc.ny = static_cast<int32_t>(std::lround((hi[1] - lo[1]) / w->desc.res));
  w->desc.nz = static_cast<int32_t>(std::lround((hi[2] - lo[2]) / w->desc.res));
  return true;
}

double lo_of(const World& w, int a) {
  return a == 0 ? w.desc.origin.x : a == 1 ? w.desc.origin.y : w.desc.origin.z;
}
double hi_of(const World& w, int a) {
  const int32_t n = a == 0 ? w.desc.nx : a == 1 ? w.desc.ny : w.desc.nz;
  return lo_of(w, a) + n * w.desc.res;
}
double& at(tdo_vec3& p, int a) { return a == 0 ? p.x : a == 1 ? p.y : p.z; }
double at(const tdo_vec3& p, int a) { return a == 0 ? p.x : a == 1 ? p.y : p.z; }

/** The test's reading of the geometry. */
struct Model {
  const World& w;
  double clearance;

  bool in_bounds(const tdo_vec3& p) const {  // half-open [lo, hi) per axis
    for (int a = 0; a < 3; ++a)
      if (!(at(p, a) >= lo_of(w, a) && at(p, a) < hi_of(w, a))) return false;
    return true;
  }
  tdo_voxel voxel_of(const tdo_vec3& p) const {
    const double r = w.desc.res;
    return tdo_voxel{static_cast<int32_t>(std::floor((p.x - w.desc.origin.x) / r)),
                     static_cast<int32_t>(std::floor((p.y - w.desc.origin.y) / r)),
                     static_cast<int32_t>(std::floor((p.z - w.desc.origin.z) / r))};
  }
  double distance(const tdo_vec3& p) const {
    double d = tdo_test::kInf;
    for (const tdo_box& b : w.boxes) d = std::fmin(d, tdo_test::distance_to_box(p, b));
    return d;
  }
  /** s.0: a voxel is blocked when it meets a box interior or its centre is closer than c. */
  bool voxel_blocked(const tdo_voxel& v) const {
    tdo_test::VoxelMap g(w.desc.nx, w.desc.ny, w.desc.nz, w.desc.res, w.desc.origin);
    for (const tdo_box& b : w.boxes)
      if (tdo_test::voxel_meets_box_interior(g, v, b)) return true;
    return distance(g.center(v)) < clearance;
  }
  /** Every point of [a, b] keeps clearance + 1 cm (samples 1 cm apart; distance is
   *  1-Lipschitz, so each sample covers 5 mm either side). */
  bool segment_keeps(const tdo_vec3& a, const tdo_vec3& b) const {
    const double len = std::sqrt((b.x - a.x) * (b.x - a.x) + (b.y - a.y) * (b.y - a.y) +
                                 (b.z - a.z) * (b.z - a.z));
    const int n = static_cast<int>(std::ceil(len / 0.01)) + 1;
    for (int i = 0; i <= n; ++i) {
      const double u = static_cast<double>(i) / n;
      const tdo_vec3 p{a.x + u * (b.x - a.x), a.y + u * (b.y - a.y), a.z + u * (b.z - a.z)};
      if (distance(p) < clearance + 0.01) return false;
    }
    return true;
  }
  /** The raw search's status for these ends (bounds, equality, the centre rule), in its order. */
  tdo_status search_status(const tdo_vec3& s, const tdo_vec3& g) const {
    if (!in_bounds(s)) return TDO_ERR_START_OUT_OF_BOUNDS;
    if (!in_bounds(g)) return TDO_ERR_GOAL_OUT_OF_BOUNDS;
    if (std::memcmp(&s, &g, sizeof(s)) == 0) return TDO_ERR_START_EQUALS_GOAL;  // (no -0.0 here)
    if (voxel_blocked(voxel_of(s))) return TDO_ERR_START_BLOCKED;
    if (voxel_blocked(voxel_of(g))) return TDO_ERR_GOAL_BLOCKED;
    return TDO_OK;
  }
  /** The planner's: the search's, then the exact points keep the clearance (s.0). */
  tdo_status plan_status(const tdo_vec3& s, const tdo_vec3& g) const {
    const tdo_status st = search_status(s, g);
    if (st != TDO_OK) return st;
    if (distance(s) < clearance) return TDO_ERR_START_BLOCKED;
    if (distance(g) < clearance) return TDO_ERR_GOAL_BLOCKED;
    return TDO_OK;
  }
};

/** A planner holding world `w` at `clearance`, asked for one pair of ends three ways. */
class Ends {
 public:
  Ends(const World& w, double clearance) : m_{w, clearance}, pl_(cap_for(w, clearance)) {
    ok_ = pl_.status() == TDO_OK &&
          tdo_test::load_grid(pl_.grid(), w.desc, w.boxes, clearance) == TDO_OK;
  }
  bool ok() const { return ok_; }
  const Model& model() const { return m_; }

  /** Asks the raw search and the planner at depths SEARCH and CORRECT for s -> g and checks each
   *  status against the model; a pair the model plans with a clear segment must take the direct
   *  route at depth CORRECT. */
  void check(const tdo_vec3& s, const tdo_vec3& g, const std::string& what) {
    SCOPED_TRACE(what + " start (" + xyz(s) + ") goal (" + xyz(g) + ")");
    tdo_plan_request req{};
    tdo_plan_params_default(&req.params);
    req.start = s;
    req.goal = g;
    tdo_search_input in{};
    in.grid = pl_.grid();
    in.start = s;
    in.goal = g;
    tdo_plan_search_input(&req.params, &in);
    tdo_search_output so{};
    const tdo_status raw = tdo_search_run(pl_.search(), &in, &so);
    tdo_plan_result r{};
    req.params.depth = TDO_PLAN_SEARCH;
    const tdo_status at_search = tdo_planner_plan(pl_.planner(), &req, &r);
    req.params.depth = TDO_PLAN_CORRECT;
    const tdo_status at_correct = tdo_planner_plan(pl_.planner(), &req, &r);
    const tdo_status want_search = m_.search_status(s, g);
    const tdo_status want_plan = m_.plan_status(s, g);
    // Bad ends: the named status. Good ends: no end status; whether the search then finds a
    // path (or runs out of budget) is not this test's business, but both depths agree on it.
    expect_status(raw, want_search, "raw search");
    expect_status(at_search, want_plan, "planner, depth search");
    expect_status(at_correct, want_plan, "planner, depth correct");
    if (want_plan != TDO_OK) {
      EXPECT_EQ(r.search.direct, 0u) << "a refused query took the direct route";
    }
    if (want_plan == TDO_OK && m_.segment_keeps(s, g)) {
      EXPECT_EQ(at_correct, TDO_OK);
      EXPECT_EQ(r.search.direct, 1u) << "a clear segment between good ends is the direct route";
    } else if (want_plan == TDO_OK) {
      EXPECT_EQ(tdo_status_str(at_search), tdo_status_str(raw)) << "planner and raw search differ";
    }
  }

  static bool end_status(tdo_status st) {
    return st == TDO_ERR_START_OUT_OF_BOUNDS || st == TDO_ERR_GOAL_OUT_OF_BOUNDS ||
           st == TDO_ERR_START_EQUALS_GOAL || st == TDO_ERR_START_BLOCKED ||
           st == TDO_ERR_GOAL_BLOCKED;
  }
  static void expect_status(tdo_status got, tdo_status want, const char* who) {
    if (want != TDO_OK) {
      EXPECT_STREQ(tdo_status_str(got), tdo_status_str(want)) << who;
    } else {
      EXPECT_FALSE(end_status(got)) << who << ": good ends refused with " << tdo_status_str(got);
    }
  }

 private:
  static tdo_capacity cap_for(const World& w, double clearance) {
    tdo_capacity cap{};
    tdo_capacity_for_grid(&cap, w.desc.nx, w.desc.ny, w.desc.nz, clearance / w.desc.res, 27u, 0u);
    cap.max_boxes = static_cast<uint32_t>(w.boxes.size() + 1u);
    return cap;
  }
  static std::string xyz(const tdo_vec3& p) {
    std::ostringstream os;
    os.precision(17);
    os << p.x << ", " << p.y << ", " << p.z;
    return os.str();
  }
  Model m_;
  TestPlanner pl_;
  bool ok_ = false;
};

/** A room off the origin with one pillar: 12 x 10 x 6 m at 0.5 m voxels. */
World room() {
  World w;
  w.desc = tdo_grid_desc{24, 20, 12, 0.5, tdo_vec3{-3.5, 1.25, -1.0}};
  w.boxes.push_back(tdo_box{tdo_vec3{3.0, 5.0, -1.0}, tdo_vec3{4.0, 6.0, 5.0}});
  return w;
}

// A start walking along a line that enters the map through a face (and, for the second line, an
// edge and a corner of the bounds) and leaves it through the opposite one, in steps that land
// exactly on the faces: outside and on a max face it is out of bounds, on a min face and inside
// it is a start (and a goal) like any other, planned by the direct route when the segment is clear.
TEST(SearchEnds, GivenAStartOnALineEnteringTheMap_WhenPlanningDirectOrBySearch_ThenTheyAgree) {
  const World w = room();
  Ends e(w, 0.5);
  ASSERT_TRUE(e.ok());
  const tdo_vec3 inner{-1.0, 3.0, 1.5};  // free, the segments to the lines' points clear
  // Along x at y = 4.25, z = 2.0 (x from 1 m before the min face to 1 m past the max face).
  for (int i = -4; i <= 52; ++i) {
    const tdo_vec3 p{-3.5 + 0.25 * i, 4.25, 2.0};
    e.check(p, inner, "x line, start");
    e.check(inner, p, "x line, goal");
  }
  // The diagonal through the corner (-3.5, 1.25, -1.0) and into the map.
  for (int i = -3; i <= 6; ++i) {
    const tdo_vec3 p{-3.5 + 0.25 * i, 1.25 + 0.25 * i, -1.0 + 0.25 * i};
    e.check(p, inner, "corner diagonal, start");
    e.check(inner, p, "corner diagonal, goal");
  }
  // Along z at the max x face: every point of it out of bounds, whatever its height.
  for (int i = -2; i <= 26; ++i) {
    const tdo_vec3 p{8.5, 4.25, -1.0 + 0.25 * i};
    e.check(p, inner, "on the max x face, start");
  }
  // Beside the pillar (its face at x = 4) at clearance 0.9: points of voxel [4.5, 5) keep the
  // clearance from x = 4.9 on, while the voxel's centre (0.75 m away) is blocked; the voxel
  // [4, 4.5) is blocked with all its points too close.
  Ends far(w, 0.9);
  ASSERT_TRUE(far.ok());
  const tdo_vec3 away{7.0, 9.0, 2.0};
  for (int k = 1; k <= 23; ++k) {
    const tdo_vec3 p{4.0 + k / 16.0, 5.5, 2.0};
    far.check(p, away, "beside the pillar, start");
    far.check(away, p, "beside the pillar, goal");
  }
  e.check(inner, inner, "start equals goal");
}

// Map1-5 (docs/design.md s.9) at two clearances: every kind of bad end (out of bounds past each
// face, on each max face, inside a box, in a voxel blocked by the centre rule, a point too close
// in a free voxel) and the good ends beside them, the map's own query included.
TEST(SearchEnds, GivenEachBadEndOnMaps1To5_WhenPlanningDirectOrBySearch_ThenTheNamedStatus) {
  for (int n = 1; n <= 5; ++n) {
    World w;
    const std::string path =
        std::string(TDO_SOURCE_DIR) + "/maps/map" + std::to_string(n) + ".tdomap";
    ASSERT_TRUE(read_tdomap(path, &w)) << path;
    for (double clearance : {0.5, 0.8}) {
      SCOPED_TRACE("map" + std::to_string(n) + " clearance " + std::to_string(clearance));
      Ends e(w, clearance);
      ASSERT_TRUE(e.ok());
      const Model& m = e.model();
      ASSERT_EQ(m.plan_status(w.start, w.goal), TDO_OK) << "the map's own query is good";
      // The map's query at depth SEARCH and CORRECT (no direct route: Map1-5 need a search).
      e.check(w.start, w.goal, "the map's query");
      // A good point 2.5 m from p (else the map's goal): the other end of a case at p.
      const auto near = [&](const tdo_vec3& p) {
        for (const tdo_vec3 step : {tdo_vec3{2.5, 0, 0}, tdo_vec3{0, 2.5, 0}, tdo_vec3{-2.5, 0, 0},
                                    tdo_vec3{0, -2.5, 0}, tdo_vec3{0, 0, 2.5}}) {
          const tdo_vec3 q{p.x + step.x, p.y + step.y, p.z + step.z};
          if (m.plan_status(q, w.start) == TDO_OK) return q;
        }
        return w.goal;
      };
      // The map's start and goal moved past each face (0.5 m out) and onto it: min faces are
      // inside, max faces are not.
      for (int a = 0; a < 3; ++a) {
        for (double off : {-0.5, 0.0}) {
          for (const tdo_vec3& end : {w.start, w.goal}) {
            tdo_vec3 p = end;
            at(p, a) = lo_of(w, a) + off;
            e.check(p, near(p), "start at the min face of axis " + std::to_string(a));
            e.check(near(p), p, "goal at the min face of axis " + std::to_string(a));
            at(p, a) = hi_of(w, a) - off;
            e.check(p, near(p), "start at the max face of axis " + std::to_string(a));
            e.check(near(p), p, "goal at the max face of axis " + std::to_string(a));
          }
        }
      }
      // On a face with a clear segment 2.5 m inwards: on a max face the closed bounds hold the
      // segment, so only the ends' check keeps the direct route from planning it.
      int tempting = 0;
      for (int a = 0; a < 3; ++a)
        for (int side = 0; side < 2; ++side) {
          int found = 0;
          for (double u = 1.25; u + 1.0 < hi_of(w, (a + 1) % 3) && found < 4; u += 2.0) {
            tdo_vec3 f{0.0, 0.0, 0.0};
            at(f, a) = side == 0 ? lo_of(w, a) : hi_of(w, a);
            at(f, (a + 1) % 3) = lo_of(w, (a + 1) % 3) + u;
            at(f, (a + 2) % 3) =
                lo_of(w, (a + 2) % 3) + std::fmod(0.5 * u + 0.75, hi_of(w, (a + 2) % 3) - 1.0);
            tdo_vec3 in = f;
            at(in, a) += side == 0 ? 2.5 : -2.5;
            if (!m.segment_keeps(f, in)) continue;
            ++found;
            e.check(f, in, "face start, clear segment");
            e.check(in, f, "face goal, clear segment");
          }
          tempting += found;
        }
      EXPECT_GE(tempting, 6) << "few clear segments at the faces";
      // Inside a box and at points beside and above boxes: blocked by the centre rule (with or
      // without the point itself keeping the clearance) or free with the point too close,
      // either way refused with the end's status; or good. The other end: a free point nearby.
      int boxes = 0;
      for (const tdo_box& b : w.boxes) {
        if (boxes++ >= 12) break;
        const tdo_vec3 c{0.5 * (b.min.x + b.max.x), 0.5 * (b.min.y + b.max.y),
                         0.5 * (b.min.z + b.max.z)};
        e.check(c, w.start, "start inside a box");
        e.check(w.start, c, "goal inside a box");
        for (double d : {0.1, 0.3, 0.45, 0.55, 0.7, 0.95}) {
          for (const tdo_vec3& p :
               {tdo_vec3{b.max.x + d, c.y, c.z}, tdo_vec3{c.x, c.y, b.max.z + d}}) {
            if (!m.in_bounds(p)) continue;
            const tdo_vec3 other = near(p);
            e.check(p, other, "start beside a box");
            e.check(other, p, "goal beside a box");
          }
        }
      }
    }
  }
}

}  // namespace
