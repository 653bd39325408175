// Tests of the OctoMap input of mapio: voxelization of .bt and .ot OcTrees checked against the
// OctoMap API itself (node searches and leaf counts), the shipped trees, and the error messages.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <octomap/OcTree.h>
#include <unistd.h>

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string>
#include <tuple>
#include <vector>

#include "tdo/tdo.h"
#include "tdo_io/map_io.h"

namespace fs = std::filesystem;
using ::testing::EndsWith;
using ::testing::HasSubstr;
using ::testing::StartsWith;

namespace {

const std::string kMaps = std::string(TDO_SOURCE_DIR) + "/maps";

class Octomap : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::temp_directory_path() / ("tdo_octomap_" + std::string(info->name()) + "_" +
                                        std::to_string(static_cast<long>(::getpid())));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  fs::path dir_;
};

using Key = std::tuple<int32_t, int32_t, int32_t>;

std::set<Key> voxel_set(const tdo_io::Map& m) {
  std::set<Key> s;
  for (const tdo_voxel& v : m.voxels) s.emplace(v.i, v.j, v.k);
  return s;
}

/** Is the point inside an occupied node of the tree (OctoMap's own search)? */
bool occupied_at(const octomap::OcTree& t, double x, double y, double z) {
  const octomap::OcTreeNode* n = t.search(x, y, z);
  return n != nullptr && t.isNodeOccupied(n);
}

/**
 * Expected voxels when the grid cells are unions of 2^s x 2^s x 2^s finest tree cells (grid
 * resolution = tree resolution * f, f = 1 or 2, origin on the tree's cell grid): a voxel is
 * occupied iff one of its finest cells is, asked through OcTree::search at the cell centres.
 */
std::set<Key> expected_by_search(const octomap::OcTree& t, const tdo_io::Map& m, int f) {
  std::set<Key> s;
  const double r = t.getResolution();
  const tdo_grid_desc& d = m.desc;
  for (int32_t k = 0; k < d.nz; ++k)
    for (int32_t j = 0; j < d.ny; ++j)
      for (int32_t i = 0; i < d.nx; ++i) {
        bool occ = false;
        for (int c = 0; c < f * f * f && !occ; ++c) {
          const double x = d.origin.x + i * d.res + (c % f + 0.5) * r;
          const double y = d.origin.y + j * d.res + ((c / f) % f + 0.5) * r;
          const double z = d.origin.z + k * d.res + (c / (f * f) + 0.5) * r;
          occ = occupied_at(t, x, y, z);
        }
        if (occ) s.emplace(i, j, k);
      }
  return s;
}

/** Occupied finest cells of the tree: sum over occupied leaves of (leaf size / res)^3. */
uint64_t occupied_cells(const octomap::OcTree& t) {
  uint64_t n = 0;
  for (auto it = t.begin_leafs(), end = t.end_leafs(); it != end; ++it) {
    if (!t.isNodeOccupied(*it)) continue;
    const auto edge = static_cast<uint64_t>(std::llround(it.getSize() / t.getResolution()));
    n += edge * edge * edge;
  }
  return n;
}

/** A small tree: a few occupied cells, one pruned 0.2 m block, free cells widening the bounds. */
octomap::OcTree small_tree() {
  octomap::OcTree t(0.1);
  for (const auto& p :
       {octomap::point3d(0.05f, 0.05f, 0.05f), octomap::point3d(1.25f, 0.35f, 0.15f),
        octomap::point3d(-0.75f, 0.95f, 0.45f)})
    t.updateNode(p, true);
  for (int c = 0; c < 8; ++c)  // the 8 cells of [0.4, 0.6]^3 merge into one depth-15 leaf
    t.updateNode(octomap::point3d(0.45f + 0.1f * static_cast<float>(c & 1),
                                  0.45f + 0.1f * static_cast<float>((c >> 1) & 1),
                                  0.45f + 0.1f * static_cast<float>((c >> 2) & 1)),
                 true);
  t.updateNode(octomap::point3d(-1.15f, -0.55f, 0.85f), false);
  t.updateNode(octomap::point3d(1.95f, 1.45f, -0.25f), false);
  t.toMaxLikelihood();
  t.prune();
  return t;
}

// ------------------------------------------------------------------------------------ small tree

TEST_F(Octomap, GivenSmallTreeAsBtAndOtThenVoxelsMatchTheTreeSearch) {
  octomap::OcTree t = small_tree();
  bool pruned_block = false;
  for (auto it = t.begin_leafs(), end = t.end_leafs(); it != end; ++it)
    pruned_block |= t.isNodeOccupied(*it) && it.getDepth() == 15;
  ASSERT_TRUE(pruned_block) << "the test tree should hold a pruned occupied leaf";
  ASSERT_TRUE(t.writeBinary(path("t.bt")));
  ASSERT_TRUE(t.write(path("t.ot")));
  double lo[3];
  double hi[3];
  t.getMetricMin(lo[0], lo[1], lo[2]);
  t.getMetricMax(hi[0], hi[1], hi[2]);

  for (const char* name : {"t.bt", "t.ot"}) {
    tdo_io::Map m;
    std::string err;
    ASSERT_TRUE(tdo_io::load_map(path(name), &m, &err)) << err;
    EXPECT_EQ(m.kind, tdo_io::MapKind::OctoMap);
    EXPECT_DOUBLE_EQ(m.desc.res, 0.1);
    // Bounds: known space (-1.2 .. 2.0, -0.6 .. 1.5, -0.3 .. 0.9) padded by one voxel.
    EXPECT_NEAR(m.desc.origin.x, lo[0] - 0.1, 1e-9);
    EXPECT_NEAR(m.desc.origin.y, lo[1] - 0.1, 1e-9);
    EXPECT_NEAR(m.desc.origin.z, lo[2] - 0.1, 1e-9);
    EXPECT_EQ(m.desc.nx, static_cast<int32_t>(std::lround((hi[0] - lo[0]) / 0.1)) + 2);
    EXPECT_EQ(m.desc.ny, static_cast<int32_t>(std::lround((hi[1] - lo[1]) / 0.1)) + 2);
    EXPECT_EQ(m.desc.nz, static_cast<int32_t>(std::lround((hi[2] - lo[2]) / 0.1)) + 2);
    EXPECT_EQ(m.voxels.size(), 3u + 8u);
    EXPECT_EQ(voxel_set(m), expected_by_search(t, m, 1)) << name;
  }

  // Finer grid: every 0.1 m cell becomes 2 x 2 x 2 voxels of 0.05 m.
  tdo_io::LoadOptions fine;
  fine.resolution = 0.05;
  tdo_io::Map m;
  std::string err;
  ASSERT_TRUE(tdo_io::load_map(path("t.bt"), fine, &m, &err)) << err;
  EXPECT_EQ(m.voxels.size(), 8u * (3u + 8u));
  // Coarser grid: a voxel is occupied when any of its 8 cells is.
  tdo_io::LoadOptions coarse;
  coarse.resolution = 0.2;
  ASSERT_TRUE(tdo_io::load_map(path("t.ot"), coarse, &m, &err)) << err;
  EXPECT_EQ(voxel_set(m), expected_by_search(t, m, 2));
}

TEST_F(Octomap, GivenUnalignedResolutionThenExactlyTheVoxelsTheLeavesIntersect) {
  octomap::OcTree t = small_tree();
  ASSERT_TRUE(t.writeBinary(path("t.bt")));
  tdo_io::LoadOptions opt;
  opt.resolution = 0.15;
  tdo_io::Map m;
  std::string err;
  ASSERT_TRUE(tdo_io::load_map(path("t.bt"), opt, &m, &err)) << err;
  // Brute force: a voxel is occupied iff its open box overlaps an occupied leaf's open cube.
  std::set<Key> expected;
  const tdo_grid_desc& d = m.desc;
  for (auto it = t.begin_leafs(), end = t.end_leafs(); it != end; ++it) {
    if (!t.isNodeOccupied(*it)) continue;
    const double h = it.getSize() / 2;
    const double c[3] = {it.getX(), it.getY(), it.getZ()};
    for (int32_t k = 0; k < d.nz; ++k)
      for (int32_t j = 0; j < d.ny; ++j)
        for (int32_t i = 0; i < d.nx; ++i) {
          const double v[3] = {d.origin.x + i * d.res, d.origin.y + j * d.res,
                               d.origin.z + k * d.res};
          bool overlap = true;
          for (int a = 0; a < 3; ++a)
            overlap = overlap && v[a] < c[a] + h - 1e-9 && v[a] + d.res > c[a] - h + 1e-9;
          if (overlap) expected.emplace(i, j, k);
        }
  }
  EXPECT_EQ(voxel_set(m), expected);
}

// ------------------------------------------------------------------------------------ shipped
// trees

TEST(OctomapData, GivenGeb079ThenBuildingFloorDimsAndEveryOccupiedCell) {
  const std::string file = kMaps + "/octomap/geb079.bt";
  octomap::OcTree t(0.1);
  ASSERT_TRUE(t.readBinary(file));
  tdo_io::Map m;
  std::string err;
  ASSERT_TRUE(tdo_io::load_map(file, &m, &err)) << err;
  EXPECT_DOUBLE_EQ(m.desc.res, 0.08);
  // About 39 x 15 x 3 m of space at 8 cm, plus one voxel on each side.
  EXPECT_EQ(m.desc.nx, 489);
  EXPECT_EQ(m.desc.ny, 189);
  EXPECT_EQ(m.desc.nz, 41);
  EXPECT_EQ(m.voxels.size(), occupied_cells(t));
  EXPECT_EQ(m.voxels.size(), 185673u);
  // Spot check against the tree's own search: every 5th voxel of the grid.
  const tdo_grid_desc& d = m.desc;
  const std::set<Key> got = voxel_set(m);
  std::size_t checked = 0;
  for (int64_t n = 0; n < static_cast<int64_t>(d.nx) * d.ny * d.nz; n += 5) {
    const auto i = static_cast<int32_t>(n % d.nx);
    const auto j = static_cast<int32_t>((n / d.nx) % d.ny);
    const auto k = static_cast<int32_t>(n / (static_cast<int64_t>(d.nx) * d.ny));
    const bool occ = occupied_at(t, d.origin.x + (i + 0.5) * d.res, d.origin.y + (j + 0.5) * d.res,
                                 d.origin.z + (k + 0.5) * d.res);
    ASSERT_EQ(occ, got.count(Key(i, j, k)) == 1) << i << " " << j << " " << k;
    ++checked;
  }
  EXPECT_GT(checked, 700000u);
}

TEST(OctomapData, GivenForest0ThenTenByTenMetresAndTheSearchAgreesAtTwoResolutions) {
  const std::string file = kMaps + "/forest_gen/forest0.bt";
  octomap::OcTree t(0.1);
  ASSERT_TRUE(t.readBinary(file));
  tdo_io::Map m;
  std::string err;
  ASSERT_TRUE(tdo_io::load_map(file, &m, &err)) << err;
  EXPECT_DOUBLE_EQ(m.desc.res, 0.1);
  EXPECT_EQ(m.desc.nx, 102);  // 10 m + 2 voxels
  EXPECT_EQ(m.desc.ny, 102);
  EXPECT_EQ(m.desc.nz, 52);  // 5 m + 2 voxels
  EXPECT_NEAR(m.desc.origin.x, -5.1, 1e-9);
  EXPECT_EQ(m.voxels.size(), occupied_cells(t));
  EXPECT_EQ(voxel_set(m), expected_by_search(t, m, 1));

  tdo_io::LoadOptions coarse;
  coarse.resolution = 0.2;
  ASSERT_TRUE(tdo_io::load_map(file, coarse, &m, &err)) << err;
  EXPECT_EQ(m.desc.nx, 52);
  EXPECT_EQ(voxel_set(m), expected_by_search(t, m, 2));
}

TEST(OctomapData, GivenForestsAndTheirCsvThenPublishedStartsAreInsideTheGrids) {
  std::ifstream csv(kMaps + "/forest_gen/start_and_end.csv");
  ASSERT_TRUE(csv);
  std::string line;
  std::getline(csv, line);
  EXPECT_EQ(line, "#trial,map_id,start_x,start_y,start_z,end_x,end_y,end_z");
  int rows = 0;
  while (std::getline(csv, line)) {
    std::istringstream in(line);
    std::string cell;
    std::vector<double> v;
    while (std::getline(in, cell, ',')) v.push_back(std::stod(cell));
    ASSERT_EQ(v.size(), 8u);
    if (v[1] > 2.0) continue;
    ++rows;
    for (int a = 0; a < 2; ++a) {
      EXPECT_GT(v[2 + a], -5.0);
      EXPECT_LT(v[2 + a], 5.0);
      EXPECT_GT(v[5 + a], -5.0);
      EXPECT_LT(v[5 + a], 5.0);
    }
  }
  EXPECT_EQ(rows, 300);
}

// ------------------------------------------------------------------------------------ errors

TEST_F(Octomap, GivenBadFilesThenClearErrorsAndNothingOnStderr) {
  tdo_io::Map m;
  std::string err;
  const std::string missing = path("none.bt");
  EXPECT_FALSE(tdo_io::load_map(missing, &m, &err));
  EXPECT_EQ(err, missing + ": cannot open");

  const std::string text = path("text.bt");
  std::ofstream(text) << "tdomap 1\nbounds 0 0 0 1 1 1\n";
  EXPECT_FALSE(tdo_io::load_map(text, &m, &err));
  EXPECT_THAT(err, StartsWith(text + ": not an OctoMap file"));
  const std::string empty_file = path("zero.ot");
  std::ofstream(empty_file).close();
  EXPECT_FALSE(tdo_io::load_map(empty_file, &m, &err));
  EXPECT_THAT(err, StartsWith(empty_file + ": not an OctoMap file"));

  // A binary tree cut short: refused by the stream check before the OctoMap library reads it.
  std::ifstream in(kMaps + "/forest_gen/forest0.bt", std::ios::binary);
  std::ostringstream all;
  all << in.rdbuf();
  const std::string bytes = all.str();
  ASSERT_GT(bytes.size(), 4000u);
  const std::string cut = path("cut.bt");
  std::ofstream(cut, std::ios::binary) << bytes.substr(0, 3000);
  ::testing::internal::CaptureStderr();
  const bool ok = tdo_io::load_map(cut, &m, &err);
  const std::string printed = ::testing::internal::GetCapturedStderr();
  EXPECT_FALSE(ok);
  EXPECT_THAT(err, StartsWith(cut + ": corrupt OcTree (node_count)"));
  EXPECT_EQ(printed, "");

  // A good tree prints nothing either (OctoMap announces every read on stderr otherwise).
  ::testing::internal::CaptureStderr();
  EXPECT_TRUE(tdo_io::load_map(kMaps + "/forest_gen/forest1.bt", &m, &err)) << err;
  EXPECT_EQ(::testing::internal::GetCapturedStderr(), "");

  octomap::OcTree nothing(0.1);
  ASSERT_TRUE(nothing.writeBinary(path("empty.bt")));
  EXPECT_FALSE(tdo_io::load_map(path("empty.bt"), &m, &err));
  EXPECT_EQ(err, path("empty.bt") +
                     ": corrupt OcTree (node_count): the header gives no nodes ('size 0' or none)");
}

TEST_F(Octomap, GivenTooManyVoxelsOrBadResolutionThenError) {
  const std::string file = kMaps + "/forest_gen/forest0.bt";
  tdo_io::Map m;
  std::string err;
  tdo_io::LoadOptions cap;
  cap.max_voxels = 100000;
  EXPECT_FALSE(tdo_io::load_map(file, cap, &m, &err));
  EXPECT_THAT(err, StartsWith(file + ": grid too large: 102 x 102 x 52 = 541008 voxels"));
  EXPECT_THAT(err, HasSubstr("cap of 100000"));
  // The bytes it would need: the footprint of a planner holding just this grid.
  tdo_planner_config grid_only{};
  tdo_capacity_for_grid(&grid_only.cap, 102, 102, 52, 0.0, 1u, 1u);
  EXPECT_THAT(err, EndsWith("; its grid alone needs an arena of " +
                            std::to_string(tdo_planner_footprint(&grid_only)) + " bytes"));
  EXPECT_GT(tdo_planner_footprint(&grid_only), 541008u * 9u);  // flags, moves, distance field
  tdo_io::LoadOptions tiny;
  tiny.resolution = 0.001;
  EXPECT_FALSE(tdo_io::load_map(file, tiny, &m, &err));
  EXPECT_THAT(err, HasSubstr("grid too large"));
  tdo_io::LoadOptions neg;
  neg.resolution = -0.1;
  EXPECT_FALSE(tdo_io::load_map(file, neg, &m, &err));
  EXPECT_THAT(err, EndsWith("resolution must be finite and >= 0 (0 = the tree's)"));
  neg.resolution = std::nan("");
  EXPECT_FALSE(tdo_io::load_map(file, neg, &m, &err));
}

TEST_F(Octomap, GivenOctreeMapThenLibtdoPlansThroughTheForest) {
  tdo_io::Map m;
  std::string err;
  ASSERT_TRUE(tdo_io::load_map(kMaps + "/forest_gen/forest0.bt", &m, &err)) << err;
  tdo_planner_config cfg{};
  cfg.cap = tdo_io::capacity_for(m, 0.5, 1, 0);
  std::vector<unsigned char> arena(tdo_planner_footprint(&cfg));
  tdo_planner* planner = nullptr;
  ASSERT_EQ(tdo_planner_init(&planner, arena.data(), arena.size(), &cfg), TDO_OK);
  ASSERT_EQ(tdo_io::load_into(m, tdo_planner_grid(planner), 0.5), TDO_OK);
  // Trial 0 of start_and_end.csv (map 0).
  tdo_search_input in{};
  in.grid = tdo_planner_grid(planner);
  in.start = tdo_vec3{-1.723340, -4.168233, 1.0};
  in.goal = tdo_vec3{3.230813, 0.271203, 1.0};
  in.kind = TDO_SEARCH_BIDIR;
  tdo_search_output out{};
  ASSERT_EQ(tdo_search_run(tdo_planner_search(planner), &in, &out), TDO_OK);
  const double straight = std::hypot(in.goal.x - in.start.x, in.goal.y - in.start.y);
  EXPECT_GE(out.cost, straight - 0.2);
  EXPECT_LT(out.cost, 2.0 * straight);
}

}  // namespace
