// Tests of the map and scenario readers (mapio/).
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

#include "tdo/tdo.h"
#include "tdo_io/map_io.h"

namespace fs = std::filesystem;
using ::testing::HasSubstr;
using ::testing::StartsWith;

namespace {

/** A fresh temporary directory per test, removed afterwards. */
class MapIo : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::temp_directory_path() / ("tdo_io_" + std::string(info->name()) + "_" +
                                        std::to_string(static_cast<long>(::getpid())));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  /** Write `text` to DIR/name and return the path. */
  std::string write(const std::string& name, const std::string& text) {
    const std::string path = (dir_ / name).string();
    std::ofstream(path, std::ios::binary) << text;
    return path;
  }

  /** Load a .tdomap with `body` after the three header lines; return the error ("" on success). */
  std::string tdomap_error(const std::string& body) {
    const std::string path =
        write("m.tdomap", "tdomap 1\nbounds 0 0 0 10 10 4\nresolution 0.5\n" + body);
    tdo_io::Map map;
    std::string err;
    const bool ok = tdo_io::load_map(path, &map, &err);
    EXPECT_EQ(ok, err.empty()) << err;
    return err;
  }

  fs::path dir_;
};

constexpr const char* kGood =
    "# comment line\n"
    "\n"
    "tdomap 1   # header with a comment\n"
    "bounds -1 -2 0   9 8 3.2\n"
    "resolution 0.5\n"
    "   \t\n"
    "box 4 0 0  6 8 4   # wall\n"
    "box 1 1 1 2 2 2\n"
    "start 0 5 1\n"
    "goal  8.5 1 1\n"
    "mover 7  5 5 2  0.5 -0.5 0  0.3\n";

}  // namespace

// ------------------------------------------------------------------------------------ .tdomap

TEST_F(MapIo, GivenGoodTdomapWhenLoadedThenEveryFieldIsRead) {
  const std::string path = write("good.tdomap", kGood);
  tdo_io::Map map;
  std::string err;
  ASSERT_TRUE(tdo_io::load_map(path, &map, &err)) << err;
  EXPECT_TRUE(err.empty());
  EXPECT_EQ(map.kind, tdo_io::MapKind::TdoMap);
  EXPECT_EQ(map.path, path);
  EXPECT_EQ(map.desc.nx, 20);
  EXPECT_EQ(map.desc.ny, 20);
  EXPECT_EQ(map.desc.nz, 7);  // ceil(3.2 / 0.5)
  EXPECT_DOUBLE_EQ(map.desc.res, 0.5);
  EXPECT_DOUBLE_EQ(map.desc.origin.x, -1.0);
  EXPECT_DOUBLE_EQ(map.desc.origin.y, -2.0);
  EXPECT_DOUBLE_EQ(map.desc.origin.z, 0.0);
  ASSERT_EQ(map.boxes.size(), 2u);
  EXPECT_DOUBLE_EQ(map.boxes[0].min.x, 4.0);
  EXPECT_DOUBLE_EQ(map.boxes[0].max.y, 8.0);
  EXPECT_DOUBLE_EQ(map.boxes[1].max.z, 2.0);
  EXPECT_TRUE(map.voxels.empty());
  EXPECT_TRUE(map.has_start);
  EXPECT_TRUE(map.has_goal);
  EXPECT_DOUBLE_EQ(map.goal.x, 8.5);
  ASSERT_EQ(map.movers.size(), 1u);
  EXPECT_EQ(map.movers[0].id, 7);
  EXPECT_DOUBLE_EQ(map.movers[0].vel.y, -0.5);
  EXPECT_DOUBLE_EQ(map.movers[0].radius, 0.3);
}

TEST_F(MapIo, GivenExtentAMultipleOfResolutionThenNoExtraVoxelFromRounding) {
  // 1 / 0.1 is 10.000000000000002 in doubles: still 10 voxels.
  const std::string path = write("r.tdomap", "tdomap 1\nbounds 0 0 0 1 0.3 0.7\nresolution 0.1\n");
  tdo_io::Map map;
  std::string err;
  ASSERT_TRUE(tdo_io::load_map(path, &map, &err)) << err;
  EXPECT_EQ(map.desc.nx, 10);
  EXPECT_EQ(map.desc.ny, 3);
  EXPECT_EQ(map.desc.nz, 7);
  EXPECT_FALSE(map.has_start);
  EXPECT_FALSE(map.has_goal);
}

TEST_F(MapIo, GivenMissingFileThenErrorNamesTheFile) {
  const std::string path = (dir_ / "nothing.tdomap").string();
  tdo_io::Map map;
  std::string err;
  EXPECT_FALSE(tdo_io::load_map(path, &map, &err));
  EXPECT_EQ(err, path + ": cannot open");
}

TEST_F(MapIo, GivenUnknownKeywordThenErrorNamesFileAndLine) {
  const std::string err = tdomap_error("\nboxx 1 1 1 2 2 2\n");
  EXPECT_THAT(err, StartsWith((dir_ / "m.tdomap").string() + ":5: "));
  EXPECT_THAT(err, HasSubstr("unknown keyword 'boxx'"));
}

TEST_F(MapIo, GivenMissingNumberThenErrorNamesFileAndLine) {
  std::string err = tdomap_error("box 1 1 1 2 2\n");
  EXPECT_THAT(err, StartsWith((dir_ / "m.tdomap").string() + ":4: "));
  EXPECT_THAT(err, HasSubstr("'box' needs 6 numbers"));
  EXPECT_THAT(err, HasSubstr("got 5"));
  err = tdomap_error("start 1 2\n");
  EXPECT_THAT(err, HasSubstr(":4: 'start' needs 3 numbers"));
  err = tdomap_error("goal\n");
  EXPECT_THAT(err, HasSubstr(":4: 'goal' needs 3 numbers"));
  err = tdomap_error("mover 1 0 0 0 0 0 0\n");
  EXPECT_THAT(err, HasSubstr(":4: 'mover' needs 8 numbers"));
}

TEST_F(MapIo, GivenExtraOrMalformedNumberThenError) {
  EXPECT_THAT(tdomap_error("box 1 1 1 2 2 2 3\n"), HasSubstr(":4: unexpected '3'"));
  EXPECT_THAT(tdomap_error("box 1 1 1 2 2 2x\n"), HasSubstr(":4: expected a number, got '2x'"));
  EXPECT_THAT(tdomap_error("start a b c\n"), HasSubstr(":4: expected a number, got 'a'"));
  EXPECT_THAT(tdomap_error("mover 1.5 0 0 0 0 0 0 1\n"),
              HasSubstr(":4: expected an integer mover id"));
}

TEST_F(MapIo, GivenNonFiniteNumberThenErrorNamesFileAndLine) {
  for (const char* tok : {"nan", "NaN", "inf", "-inf", "Infinity", "1e999"}) {
    const std::string err = tdomap_error(std::string("box 1 1 ") + tok + " 2 2 2\n");
    EXPECT_THAT(err, StartsWith((dir_ / "m.tdomap").string() + ":4: ")) << tok;
    EXPECT_THAT(err, HasSubstr(std::string("non-finite number '") + tok + "'")) << tok;
  }
  EXPECT_THAT(tdomap_error("start 1 nan 1\n"), HasSubstr(":4: non-finite number 'nan'"));
}

TEST_F(MapIo, GivenInvertedBoxThenErrorNamesFileLineAndAxis) {
  EXPECT_THAT(tdomap_error("box 3 1 1 2 2 2\n"),
              HasSubstr(":4: inverted box: max <= min on the x axis"));
  EXPECT_THAT(tdomap_error("box 1 1 1 2 1 2\n"),
              HasSubstr(":4: inverted box: max <= min on the y axis"));
  EXPECT_THAT(tdomap_error("box 1 1 5 2 2 2\n"),
              HasSubstr(":4: inverted box: max <= min on the z axis"));
}

TEST_F(MapIo, GivenBadHeaderBoundsOrResolutionThenErrorNamesFileAndLine) {
  tdo_io::Map map;
  std::string err;
  const std::string no_header =
      write("h.tdomap", "# only a comment\nbounds 0 0 0 1 1 1\nresolution 1\n");
  EXPECT_FALSE(tdo_io::load_map(no_header, &map, &err));
  EXPECT_EQ(err, no_header + ":2: missing header 'tdomap 1' (found 'bounds')");

  const std::string empty = write("e.tdomap", "");
  EXPECT_FALSE(tdo_io::load_map(empty, &map, &err));
  EXPECT_THAT(err, StartsWith(empty + ":1: missing header"));

  const std::string version = write("v.tdomap", "tdomap 2\n");
  EXPECT_FALSE(tdo_io::load_map(version, &map, &err));
  EXPECT_THAT(err, StartsWith(version + ":1: unsupported header"));

  const std::string bounds = write("b.tdomap", "tdomap 1\nresolution 1\nbounds 0 0 0 1 1 0\n");
  EXPECT_FALSE(tdo_io::load_map(bounds, &map, &err));
  EXPECT_EQ(err, bounds + ":3: bounds inverted: max <= min on the z axis");

  for (const char* r : {"0", "-0.5"}) {
    const std::string res =
        write("r.tdomap", std::string("tdomap 1\nbounds 0 0 0 1 1 1\nresolution ") + r + "\n");
    EXPECT_FALSE(tdo_io::load_map(res, &map, &err));
    EXPECT_EQ(err, res + ":3: resolution must be > 0, got " + r);
  }

  const std::string missing = write("m.tdomap", "tdomap 1\nresolution 1\n\n");
  EXPECT_FALSE(tdo_io::load_map(missing, &map, &err));
  EXPECT_THAT(err, StartsWith(missing + ":"));
  EXPECT_THAT(err, HasSubstr("missing 'bounds'"));

  const std::string dup = write("d.tdomap", "tdomap 1\nbounds 0 0 0 1 1 1\nbounds 0 0 0 1 1 1\n");
  EXPECT_FALSE(tdo_io::load_map(dup, &map, &err));
  EXPECT_EQ(err, dup + ":3: duplicate 'bounds'");

  EXPECT_THAT(tdomap_error("mover 1 0 0 0 0 0 0 0\n"), HasSubstr(":4: mover radius must be > 0"));
}

TEST_F(MapIo, GivenUnsupportedExtensionThenError) {
  tdo_io::Map map;
  std::string err;
  const std::string bt = write("tree.bt", "not really an octree");
  EXPECT_FALSE(tdo_io::load_map(bt, &map, &err));
  EXPECT_THAT(err, StartsWith(bt + ": not an OctoMap file"));  // OcTrees: test_octomap.cpp
  const std::string txt = write("map.txt", "tdomap 1\n");
  EXPECT_FALSE(tdo_io::load_map(txt, &map, &err));
  EXPECT_THAT(err, StartsWith(txt + ": unknown map format"));
}

// ------------------------------------------------------------------------------------ .3dmap

TEST_F(MapIo, GivenGood3dmapThenVoxelsAreCentredOnTheirIntegerCoordinates) {
  const std::string path = write("v.3dmap", "voxel 4 5 6\n0 0 0\n3 4 5\n\n1 2 3\n");
  tdo_io::Map map;
  std::string err;
  ASSERT_TRUE(tdo_io::load_map(path, &map, &err)) << err;
  EXPECT_EQ(map.kind, tdo_io::MapKind::MovingAI);
  EXPECT_EQ(map.desc.nx, 4);
  EXPECT_EQ(map.desc.ny, 5);
  EXPECT_EQ(map.desc.nz, 6);
  EXPECT_DOUBLE_EQ(map.desc.res, 1.0);
  EXPECT_DOUBLE_EQ(map.desc.origin.x, -0.5);
  EXPECT_DOUBLE_EQ(map.desc.origin.z, -0.5);
  ASSERT_EQ(map.voxels.size(), 3u);
  EXPECT_EQ(map.voxels[1].i, 3);
  EXPECT_EQ(map.voxels[1].j, 4);
  EXPECT_EQ(map.voxels[1].k, 5);
  EXPECT_TRUE(map.boxes.empty());
  EXPECT_FALSE(map.has_start);
}

TEST_F(MapIo, GivenBad3dmapThenErrorNamesFileAndLine) {
  tdo_io::Map map;
  std::string err;
  const std::string outside = write("o.3dmap", "voxel 4 4 4\n0 0 0\n4 0 0\n");
  EXPECT_FALSE(tdo_io::load_map(outside, &map, &err));
  EXPECT_EQ(err, outside + ":3: voxel 4 0 0 outside the declared size 4 x 4 x 4");
  const std::string negative = write("n.3dmap", "voxel 4 4 4\n0 -1 0\n");
  EXPECT_FALSE(tdo_io::load_map(negative, &map, &err));
  EXPECT_THAT(err, StartsWith(negative + ":2: voxel 0 -1 0 outside"));
  const std::string header = write("h.3dmap", "0 0 0\n");
  EXPECT_FALSE(tdo_io::load_map(header, &map, &err));
  EXPECT_EQ(err, header + ":1: missing header 'voxel X Y Z'");
  const std::string size = write("s.3dmap", "voxel 4 0 4\n");
  EXPECT_FALSE(tdo_io::load_map(size, &map, &err));
  EXPECT_THAT(err, StartsWith(size + ":1: size Y 0 is outside"));
  const std::string fields = write("f.3dmap", "voxel 4 4 4\n1 1\n");
  EXPECT_FALSE(tdo_io::load_map(fields, &map, &err));
  EXPECT_THAT(err, StartsWith(fields + ":2: expected a voxel 'x y z'"));
  const std::string frac = write("x.3dmap", "voxel 4 4 4\n1 1.5 1\n");
  EXPECT_FALSE(tdo_io::load_map(frac, &map, &err));
  EXPECT_THAT(err, StartsWith(frac + ":2: expected an integer y"));
}

// Every spelling the tokenizer takes (blanks = the "C" locale's isspace: space, \t, \r, \v, \f;
// integers as strtoll reads them: a sign, leading zeros), in the fast parse and the tokenizer
// alike, and in any order: each voxel line gives its voxel, in file order.
TEST_F(MapIo, GivenEverySpellingThe3dmapFormatAllowsThenEveryVoxelIsRead) {
  const std::string path = write("sp.3dmap",
                                 "\n  \t\n"             // blank lines before the header
                                 "voxel\t300  4 5\r\n"  // tab, two spaces, CR LF
                                 "1 2 3\n"              // plain
                                 "  1   2\t3  \r\n"     // leading/trailing blanks, CR LF
                                 "\v1\f2 3\n"           // vertical tab, form feed
                                 "+2 +0 +1\n"           // plus signs
                                 "007 0003 04\n"        // leading zeros
                                 "-0 0 -0\n"            // minus zero
                                 "0000000000299 3 4\n"  // more than nine digits
                                 " \t \r\n"             // a blank line inside
                                 "\n"                   // an empty one
                                 "1 2 3\n"              // a repeated voxel stays
                                 "299 3 4");            // no line break at the end
  tdo_io::Map map;
  std::string err;
  ASSERT_TRUE(tdo_io::load_map(path, &map, &err)) << err;
  EXPECT_EQ(map.desc.nx, 300);
  EXPECT_EQ(map.desc.ny, 4);
  EXPECT_EQ(map.desc.nz, 5);
  const int want[][3] = {{1, 2, 3}, {1, 2, 3},   {1, 2, 3}, {2, 0, 1},  {7, 3, 4},
                         {0, 0, 0}, {299, 3, 4}, {1, 2, 3}, {299, 3, 4}};
  ASSERT_EQ(map.voxels.size(), sizeof want / sizeof want[0]);
  for (std::size_t n = 0; n < map.voxels.size(); ++n) {
    EXPECT_EQ(map.voxels[n].i, want[n][0]) << "voxel " << n;
    EXPECT_EQ(map.voxels[n].j, want[n][1]) << "voxel " << n;
    EXPECT_EQ(map.voxels[n].k, want[n][2]) << "voxel " << n;
  }
}

// Errors after many good lines and blank ones: the line number and message of the tokenizer.
TEST_F(MapIo, GivenABad3dmapLineAfterManyGoodOnesThenErrorNamesItsLineAndToken) {
  std::string good = "voxel 4 4 4\n";
  for (int n = 0; n < 1000; ++n)
    good += std::to_string(n % 4) + " " + std::to_string(n % 3) + " 3\n";
  good += "\n \r\n3 3 3\n";  // lines 2 .. 1001 voxels, 1002 and 1003 blank, 1004 a voxel
  const struct {
    const char* line;
    std::string want;
  } cases[] = {
      {"4 0 0", "voxel 4 0 0 outside the declared size 4 x 4 x 4"},
      {"0 4 0", "voxel 0 4 0 outside the declared size 4 x 4 x 4"},
      {"0 0 -1", "voxel 0 0 -1 outside the declared size 4 x 4 x 4"},
      {"1 2", "expected a voxel 'x y z', got 2 fields"},
      {"1 2 3 4", "expected a voxel 'x y z', got 4 fields"},
      {"1 2 3 # note", "expected a voxel 'x y z', got 5 fields"},  // no comments in .3dmap
      {"1 2 3\r1 2 3", "expected a voxel 'x y z', got 6 fields"},  // CR alone breaks no line
      {"1 2x 3", "expected an integer y, got '2x'"},
      {"0x1 0 0", "expected an integer x, got '0x1'"},
      {"1 2 +-3", "expected an integer z, got '+-3'"},
      {"2147483648 0 0", "x 2147483648 is outside [-2147483648, 2147483647]"},
      {"1 -99999999999999999999 0", "y -99999999999999999999 is outside [-2147483648, 2147483647]"},
      {"1000000000 0 0", "voxel 1000000000 0 0 outside the declared size 4 x 4 x 4"},
  };
  for (const auto& c : cases) {
    const std::string path = write("bad.3dmap", good + c.line + "\n0 0 0\n");
    tdo_io::Map map;
    std::string err;
    EXPECT_FALSE(tdo_io::load_map(path, &map, &err)) << c.line;
    EXPECT_EQ(err, path + ":1005: " + c.want) << c.line;
  }
  const std::string path = write("good.3dmap", good);
  tdo_io::Map map;
  std::string err;
  ASSERT_TRUE(tdo_io::load_map(path, &map, &err)) << err;
  ASSERT_EQ(map.voxels.size(), 1001u);
  EXPECT_EQ(map.voxels[999].i, 3);  // n = 999: 999 % 4, 999 % 3
  EXPECT_EQ(map.voxels[999].j, 0);
  EXPECT_EQ(map.voxels[1000].i, 3);
  EXPECT_EQ(map.voxels[1000].j, 3);
}

// ------------------------------------------------------------------------------------ .3dscen

TEST_F(MapIo, GivenScenarioThenQueriesKeepTheirLineNumbers) {
  const std::string path =
      write("q.3dscen",
            "version 1\nSimple.3dmap\n56 76 52 48 85 45 15.31710829 1.054\n\n1 2 3 4 5 6 7.5 1\n");
  std::vector<tdo_io::ScenQuery> q;
  std::string err;
  ASSERT_TRUE(tdo_io::load_scen(path, &q, &err)) << err;
  ASSERT_EQ(q.size(), 2u);
  EXPECT_EQ(q[0].line, 3);
  EXPECT_DOUBLE_EQ(q[0].start.x, 56.0);
  EXPECT_DOUBLE_EQ(q[0].goal.z, 45.0);
  EXPECT_DOUBLE_EQ(q[0].cost, 15.31710829);
  EXPECT_EQ(q[1].line, 5);
}

TEST_F(MapIo, GivenBadScenarioThenErrorNamesFileAndLine) {
  std::vector<tdo_io::ScenQuery> q;
  std::string err;
  EXPECT_FALSE(tdo_io::load_scen((dir_ / "none.3dscen").string(), &q, &err));
  EXPECT_EQ(err, (dir_ / "none.3dscen").string() + ": cannot open");
  const std::string header = write("h.3dscen", "Simple.3dmap\n1 2 3 4 5 6 7 1\n");
  EXPECT_FALSE(tdo_io::load_scen(header, &q, &err));
  EXPECT_EQ(err, header + ":1: missing header 'version 1'");
  const std::string fields = write("f.3dscen", "version 1\nm.3dmap\n1 2 3 4 5 6 7 1\n1 2 3 4 5\n");
  EXPECT_FALSE(tdo_io::load_scen(fields, &q, &err));
  EXPECT_THAT(err, StartsWith(fields + ":4: expected 'sx sy sz gx gy gz cost ratio'"));
  const std::string nan = write("n.3dscen", "version 1\nm.3dmap\n1 2 3 4 5 6 nan 1\n");
  EXPECT_FALSE(tdo_io::load_scen(nan, &q, &err));
  EXPECT_EQ(err, nan + ":3: non-finite number 'nan'");
}

// ------------------------------------------------------------------------------------ real data

TEST(MapIoData, GivenMovingAiSimpleThenSizeVoxelsAndQueriesMatchTheFiles) {
  const std::string dir = std::string(TDO_SOURCE_DIR) + "/maps/movingai/";
  tdo_io::Map map;
  std::string err;
  ASSERT_TRUE(tdo_io::load_map(dir + "Simple.3dmap", &map, &err)) << err;
  EXPECT_EQ(map.desc.nx, 105);
  EXPECT_EQ(map.desc.ny, 132);
  EXPECT_EQ(map.desc.nz, 105);
  EXPECT_EQ(map.voxels.size(), 512u);
  std::vector<tdo_io::ScenQuery> q;
  ASSERT_TRUE(tdo_io::load_scen(dir + "Simple.3dmap.3dscen", &q, &err)) << err;
  ASSERT_EQ(q.size(), 10000u);
  EXPECT_EQ(q.front().line, 3);
  EXPECT_DOUBLE_EQ(q.front().cost, 15.31710829);
  EXPECT_EQ(q.back().line, 10002);
}

// ------------------------------------------------------------------------------------ into libtdo

TEST_F(MapIo, GivenGoodMapWhenLoadedIntoAPlannerThenObstaclesAndClearanceBlockVoxels) {
  const std::string path = write("good.tdomap", kGood);
  tdo_io::Map map;
  std::string err;
  ASSERT_TRUE(tdo_io::load_map(path, &map, &err)) << err;
  tdo_planner_config cfg{};
  cfg.cap = tdo_io::capacity_for(map, 0.5, 1, 0);
  EXPECT_EQ(cfg.cap.max_voxels, 20u * 20u * 7u);
  EXPECT_GE(cfg.cap.max_boxes, 2u);
  const std::size_t bytes = tdo_planner_footprint(&cfg);
  ASSERT_GT(bytes, 0u);
  std::unique_ptr<unsigned char[]> mem(new unsigned char[bytes]);
  tdo_planner* planner = nullptr;
  ASSERT_EQ(tdo_planner_init(&planner, mem.get(), bytes, &cfg), TDO_OK);
  tdo_grid* grid = tdo_planner_grid(planner);
  ASSERT_EQ(tdo_io::load_into(map, grid, 0.5), TDO_OK);
  tdo_voxel v{};
  ASSERT_EQ(tdo_grid_world_to_voxel(grid, tdo_vec3{5.0, 3.0, 2.0}, &v), 1);  // inside the wall
  EXPECT_EQ(tdo_grid_is_occupied(grid, v), 1);
  EXPECT_EQ(tdo_grid_is_blocked(grid, v), 1);
  ASSERT_EQ(tdo_grid_world_to_voxel(grid, tdo_vec3{3.8, 3.0, 2.0}, &v),
            1);  // centre 0.25 m from it
  EXPECT_EQ(tdo_grid_is_occupied(grid, v), 0);
  EXPECT_EQ(tdo_grid_is_blocked(grid, v), 1);
  ASSERT_EQ(tdo_grid_world_to_voxel(grid, tdo_vec3{0.0, 7.0, 2.0}, &v), 1);  // far from every box
  EXPECT_EQ(tdo_grid_is_blocked(grid, v), 0);

  // The search plans from the map's default query.
  tdo_search_input in{};
  in.grid = grid;
  in.start = map.start;
  in.goal = map.goal;
  in.kind = TDO_SEARCH_BIDIR;
  tdo_search_output out{};
  EXPECT_EQ(tdo_search_run(tdo_planner_search(planner), &in, &out), TDO_OK);
  EXPECT_GT(out.cost, 8.5);
  EXPECT_GE(out.n_path, 2u);
}

TEST_F(MapIo, GivenMapLargerThanCapacityThenLoadIntoReturnsMapCapacity) {
  const std::string path = write("good.tdomap", kGood);
  tdo_io::Map map;
  std::string err;
  ASSERT_TRUE(tdo_io::load_map(path, &map, &err)) << err;
  tdo_io::Map small = map;
  small.desc.nx = 2;
  small.desc.ny = 2;
  small.desc.nz = 2;
  tdo_planner_config cfg{};
  cfg.cap = tdo_io::capacity_for(small, 0.5, 1, 0);
  const std::size_t bytes = tdo_planner_footprint(&cfg);
  std::unique_ptr<unsigned char[]> mem(new unsigned char[bytes]);
  tdo_planner* planner = nullptr;
  ASSERT_EQ(tdo_planner_init(&planner, mem.get(), bytes, &cfg), TDO_OK);
  EXPECT_EQ(tdo_io::load_into(map, tdo_planner_grid(planner), 0.5), TDO_ERR_MAP_CAPACITY);
}
