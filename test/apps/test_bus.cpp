// The LCM bus on memq:// (apps/common bus.h): exact channel names, raw bytes, typed publish.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "tdo_lcm/bus.h"
#include "tdo_lcm/types.h"
#include "tdo_lcm/url.h"
#include "tdo_lcm/wire.h"

namespace {

TEST(Bus, DeliversToExactChannelsOnly) {
  tdo_lcm::Bus bus("memq://");
  ASSERT_TRUE(bus.good());
  std::vector<std::string> got;
  ASSERT_TRUE(bus.subscribe("TDO.MAP", [&](const void* d, std::size_t n, const std::string& ch) {
    got.push_back(ch + ":" + std::string(static_cast<const char*>(d), n));
  }));
  ASSERT_TRUE(bus.publish_raw("TDO.MAP", "ab", 2));
  ASSERT_TRUE(bus.publish_raw("TDOxMAP", "cd", 2));  // '.' is not a wildcard here
  ASSERT_TRUE(bus.publish_raw("TDO.MAP.2", "ef", 2));
  while (bus.handle_timeout(0) > 0) {
  }
  EXPECT_EQ(got, (std::vector<std::string>{"TDO.MAP:ab"}));
}

TEST(Bus, PublishesGeneratedMessages) {
  tdo_lcm::Bus bus("memq://");
  std::vector<tdo::status_t> got;
  ASSERT_TRUE(
      bus.subscribe(tdo_lcm::kChannelStatus, [&](const void* d, std::size_t n, const std::string&) {
        tdo::status_t s{};
        ASSERT_TRUE(tdo_lcm::decode(d, n, &s).ok());
        got.push_back(s);
      }));
  tdo::status_t s{};
  s.program = "test";
  s.seq = 41;
  ASSERT_TRUE(bus.publish(tdo_lcm::kChannelStatus, s));
  EXPECT_GT(bus.handle_timeout(100), 0);
  ASSERT_EQ(got.size(), 1u);
  EXPECT_EQ(got[0].program, "test");
  EXPECT_EQ(got[0].seq, 41);
  EXPECT_EQ(bus.handle_timeout(0), 0);  // nothing left
}

TEST(Bus, BadUrl) {
  tdo_lcm::Bus bus("nonsense://nowhere");
  EXPECT_FALSE(bus.good());
  EXPECT_FALSE(bus.subscribe("X", [](const void*, std::size_t, const std::string&) {}));
  EXPECT_FALSE(bus.publish_raw("X", "a", 1));
  EXPECT_LT(bus.handle_timeout(0), 0);
}

}  // namespace

TEST(Url, GivenAUdpmUrlWithoutReceiveBufferThenTheAppsBufferIsAdded) {
  EXPECT_EQ(tdo_lcm::with_recv_buf("udpm://239.255.76.67:7667?ttl=0"),
            "udpm://239.255.76.67:7667?ttl=0&recv_buf_size=4194304");
  EXPECT_EQ(tdo_lcm::with_recv_buf("udpm://239.255.76.67:7667"),
            "udpm://239.255.76.67:7667?recv_buf_size=4194304");
  // An explicit size stays; other providers are not touched.
  EXPECT_EQ(tdo_lcm::with_recv_buf("udpm://239.255.76.67:7667?recv_buf_size=1000"),
            "udpm://239.255.76.67:7667?recv_buf_size=1000");
  EXPECT_EQ(tdo_lcm::with_recv_buf("memq://"), "memq://");
  EXPECT_EQ(tdo_lcm::with_recv_buf("file:///tmp/x.lcmlog?speed=0"), "file:///tmp/x.lcmlog?speed=0");
  // The default URL already has it.
  EXPECT_EQ(tdo_lcm::with_recv_buf(tdo_lcm::kDefaultUrl), tdo_lcm::kDefaultUrl);
  EXPECT_NE(std::string(tdo_lcm::kDefaultUrl).find("recv_buf_size=4194304"), std::string::npos);
}
