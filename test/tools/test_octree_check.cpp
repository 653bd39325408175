// Tests of tdo_io::check_octree (the bounded OcTree stream check) and of the readers' messages on
// hostile files: trees written by the OctoMap library pass with their node counts; every
// corruption of issue 24's reproducers gets its named status; quoted text is escaped and capped.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <octomap/OcTree.h>
#include <unistd.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "tdo_io/map_io.h"
#include "tdo_io/octree_check.h"
#include "tdo_io/text.h"

namespace fs = std::filesystem;
using tdo_io::OctreeStatus;
using ::testing::HasSubstr;
using ::testing::StartsWith;

namespace {

const std::string kMaps = std::string(TDO_SOURCE_DIR) + "/maps";
const std::string kBtHeader = "# Octomap OcTree binary file\nid OcTree\nsize 9\nres 0.1\ndata\n";

std::string file_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream all;
  all << in.rdbuf();
  return all.str();
}

OctreeStatus check(const std::string& bytes, std::string* detail = nullptr,
                   tdo_io::OctreeInfo* info = nullptr) {
  return tdo_io::check_octree(reinterpret_cast<const uint8_t*>(bytes.data()), bytes.size(),
                              tdo_io::OctreeLimits{}, info, detail);
}

/** A tree of the OctoMap library with leaves at several depths, in .bt and .ot. */
octomap::OcTree library_tree() {
  octomap::OcTree t(0.1);
  for (int i = 0; i < 40; ++i)
    t.updateNode(octomap::point3d(0.1f * static_cast<float>(i), 0.05f * static_cast<float>(i % 7),
                                  -0.3f + 0.02f * static_cast<float>(i)),
                 i % 3 != 0);
  return t;
}

TEST(OctreeCheck, GivenTreesOfTheLibraryThenOkWithTheirNodeCounts) {
  for (const char* name : {"/forest_gen/forest0.bt", "/octomap/geb079.bt"}) {
    tdo_io::OctreeInfo info;
    std::string why;
    ASSERT_EQ(check(file_bytes(kMaps + name), &why, &info), OctreeStatus::ok) << name << why;
    octomap::OcTree t(0.1);
    ASSERT_TRUE(t.readBinary(kMaps + name));
    EXPECT_EQ(info.nodes, t.size());
    EXPECT_TRUE(info.binary);
    EXPECT_EQ(info.res, t.getResolution());
    EXPECT_EQ(info.depth, 16);
  }
  const octomap::OcTree t = library_tree();
  std::ostringstream bt;
  std::ostringstream ot;
  ASSERT_TRUE(t.writeBinaryConst(bt));
  ASSERT_TRUE(t.write(ot));
  tdo_io::OctreeInfo info;
  ASSERT_EQ(check(bt.str(), nullptr, &info), OctreeStatus::ok);
  EXPECT_EQ(info.nodes, t.size());
  ASSERT_EQ(check(ot.str(), nullptr, &info), OctreeStatus::ok);
  EXPECT_FALSE(info.binary);
  EXPECT_EQ(info.nodes, t.size());
}

// Issue 24's stack overflow: every node an inner node; refused within the first levels.
TEST(OctreeCheck, GivenAllInnerNodesThenTooDeep) {
  std::string why;
  std::string h = kBtHeader;
  h.replace(h.find("size 9"), 6, "size 1000");
  EXPECT_EQ(check(h + std::string(300000, '\xff'), &why), OctreeStatus::too_deep);
  EXPECT_THAT(why, HasSubstr("depth 15"));
  std::string ot = "# Octomap OcTree file\nid OcTree\nsize 20\nres 0.1\ndata\n";
  for (int i = 0; i < 20; ++i) ot += std::string("\0\0\0\0\x01", 5);
  EXPECT_EQ(check(ot, &why), OctreeStatus::too_deep);
}

TEST(OctreeCheck, GivenBadHeadersThenNamedStatus) {
  const std::string body = "\xaa\xaa";  // 8 leaves: 9 nodes
  ASSERT_EQ(check(kBtHeader + body), OctreeStatus::ok);
  std::string why;
  EXPECT_EQ(check("tdomap 1\n"), OctreeStatus::not_octomap);
  EXPECT_EQ(check(""), OctreeStatus::not_octomap);
  std::string color = kBtHeader;
  color.replace(color.find("OcTree\n"), 6, "ColorOcTree");
  EXPECT_EQ(check(color + body, &why), OctreeStatus::wrong_tree_type);
  EXPECT_THAT(why, HasSubstr("'ColorOcTree'"));
  for (const char* res : {"1e300", "1e-6", "-0.1", "nan", "inf", "0.1x", "1e999"}) {
    std::string h = kBtHeader;
    h.replace(h.find("0.1"), 3, res);
    EXPECT_EQ(check(h + body), OctreeStatus::bad_resolution) << res;
  }
  std::string no_data = kBtHeader;
  no_data.replace(no_data.find("data"), 4, "dada");
  EXPECT_EQ(check(no_data + body), OctreeStatus::bad_header);
  std::string size = kBtHeader;
  size.replace(size.find("size 9"), 6, "size -9");
  EXPECT_EQ(check(size + body), OctreeStatus::bad_header);
  size.replace(size.find("size -9"), 7, "size 4000000000");
  EXPECT_EQ(check(size + body), OctreeStatus::too_many_nodes);
  size.replace(size.find("size 4000000000"), 15, "size 99");
  EXPECT_EQ(check(size + body, &why), OctreeStatus::node_count);
  EXPECT_THAT(why, HasSubstr("2 bytes of data hold at most 9"));
}

TEST(OctreeCheck, GivenCutOrPaddedStreamsThenTruncatedOrTrailingBytes) {
  const std::string bytes = file_bytes(kMaps + "/forest_gen/forest0.bt");
  EXPECT_EQ(check(bytes.substr(0, 3000)), OctreeStatus::node_count);  // more nodes than bytes
  EXPECT_EQ(check(kBtHeader + "\xaa\xab"), OctreeStatus::truncated);  // an inner child never comes
  EXPECT_EQ(check(kBtHeader + "\xaa\xaa\n"), OctreeStatus::trailing_bytes);
  EXPECT_EQ(check(kBtHeader + "\xaa\xa8"), OctreeStatus::node_count);  // 8 nodes, not 9
  std::string ot = "# Octomap OcTree file\nid OcTree\nsize 1\nres 0.1\ndata\n";
  const float nan = std::numeric_limits<float>::quiet_NaN();
  std::string node(reinterpret_cast<const char*>(&nan), 4);
  EXPECT_EQ(check(ot + node + std::string(1, '\0')), OctreeStatus::bad_value);
}

// ---------------------------------------------------------------- the readers' messages

class HostileFiles : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("tdo_hostile_" + std::to_string(::getpid()));
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string write(const std::string& name, const std::string& bytes) const {
    const std::string p = (dir_ / name).string();
    std::ofstream(p, std::ios::binary) << bytes;
    return p;
  }
  fs::path dir_;
};

TEST_F(HostileFiles, GivenOtHeaderAndGarbageThenCorruptNotGridTooLarge) {
  std::string garbage;
  for (int i = 0; i < 40; ++i)
    for (int c = 0; c < 256; ++c) garbage.push_back(static_cast<char>(c));
  const std::string p =
      write("g.ot", "# Octomap OcTree file\nid OcTree\nsize 1000\nres 0.1\ndata\n" + garbage);
  tdo_io::Map m;
  std::string err;
  EXPECT_FALSE(tdo_io::load_map(p, &m, &err));
  EXPECT_THAT(err, StartsWith(p + ": corrupt OcTree ("));
  EXPECT_THAT(err, ::testing::Not(HasSubstr("grid too large")));
}

TEST_F(HostileFiles, GivenDirectoryThenItsOwnMessage) {
  fs::create_directories(dir_ / "d.tdomap");
  tdo_io::Map m;
  std::string err;
  EXPECT_FALSE(tdo_io::load_map((dir_ / "d.tdomap").string(), &m, &err));
  EXPECT_EQ(err, (dir_ / "d.tdomap").string() + ": is a directory, not a map file");
}

TEST_F(HostileFiles, GivenHugeTokenOrControlCharactersThenShortEscapedMessage) {
  const std::string p = write("big.tdomap", std::string(10000000, 'x'));
  tdo_io::Map m;
  std::string err;
  EXPECT_FALSE(tdo_io::load_map(p, &m, &err));
  EXPECT_LT(err.size(), 200u + p.size());
  EXPECT_THAT(err, HasSubstr("... (10000000 bytes)"));
  const std::string c = write("ctrl.tdomap", "tdomap 1\nbo\x1b[31m\x07unds 0 0 0 1 1 1\n");
  EXPECT_FALSE(tdo_io::load_map(c, &m, &err));
  EXPECT_EQ(err, c + ":2: unknown keyword 'bo\\x1b[31m\\x07unds'");
  EXPECT_EQ(tdo_io::printable("a\\b\n\xff"), "a\\\\b\\x0a\\xff");
  EXPECT_EQ(tdo_io::one_line("a\\b\n", 3), "a\\b... (4 bytes)");
}

}  // namespace
