// Fixture pieces shared by the in-process node tests (test_avoid_node.cpp, test_sim_node.cpp,
// test_planner_node.cpp, test_chain.cpp): decode-and-collect handlers, message bytes, and a memq://
// bus with the node under test.
#ifndef TDO_TEST_APPS_NODE_TEST_UTIL_H
#define TDO_TEST_APPS_NODE_TEST_UTIL_H

#include <gtest/gtest.h>

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "tdo_lcm/bus.h"
#include "tdo_lcm/wire.h"

namespace tdo_test {

/** A handler that decodes every message as Msg (expecting success) and appends it to `out`. */
template <class Msg>
tdo_lcm::Bus::Handler collect(std::vector<Msg>* out) {
  return [out](const void* data, std::size_t size, const std::string&) {
    Msg m{};
    const tdo_lcm::Check c = tdo_lcm::decode(data, size, &m);
    EXPECT_TRUE(c.ok()) << tdo_lcm::reason_str(c.reason) << ": " << c.detail;
    if (c.ok()) out->push_back(m);
  };
}

/** The LCM encoding of `m`. */
template <class Msg>
std::vector<uint8_t> bytes_of(const Msg& m) {
  std::vector<uint8_t> buf(static_cast<std::size_t>(m.getEncodedSize()));
  m.encode(buf.data(), 0, static_cast<int>(buf.size()));
  return buf;
}

/**
 * A memq:// bus and the node under test (created by the test's SetUp). `kPumpLimit` bounds the
 * messages one pump() delivers.
 */
template <class Node, class Config, int kPumpLimit>
class NodeTest : public ::testing::Test {
 protected:
  /** Deliver everything queued, including what the handlers publish meanwhile. */
  void pump() {
    for (int i = 0; i < kPumpLimit && bus_.handle_timeout(0) > 0; ++i) {
    }
  }
  template <class Msg>
  void send(const std::string& channel, const Msg& m) {
    ASSERT_TRUE(bus_.publish(channel, m));
    pump();
  }
  void send_raw(const std::string& channel, const std::vector<uint8_t>& b) {
    ASSERT_TRUE(bus_.publish_raw(channel, b.data(), b.size()));
    pump();
  }
  /** @return the node's count of `key` (0 when absent). */
  int64_t reason(const std::string& key) const {
    const auto& r = node_->counters().reasons;
    const auto it = r.find(key);
    return it == r.end() ? 0 : it->second;
  }

  tdo_lcm::Bus bus_{"memq://"};  // first: outlives the node
  Config cfg_;
  std::unique_ptr<Node> node_;
};

/** @return the count of `key` in heartbeat `s` (0 when absent). */
inline int64_t heartbeat_reason(const tdo::status_t& s, const std::string& key) {
  for (int32_t k = 0; k < s.n_reasons; ++k)
    if (s.reason[static_cast<std::size_t>(k)] == key)
      return s.reason_count[static_cast<std::size_t>(k)];
  return 0;
}

}  // namespace tdo_test

#endif  // TDO_TEST_APPS_NODE_TEST_UTIL_H
