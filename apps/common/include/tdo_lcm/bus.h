/**
 * @file bus.h
 * @brief A small owner of one LCM instance on the C API: subscribe raw bytes, publish messages.
 *
 * The apps use this instead of lcm-cpp.hpp's templated subscriptions: the handlers get the raw
 * bytes (decoded with wire.h's checks, so bad messages are counted rather than dropped with a
 * print), and there is no cast of LCM's user data to a polymorphic type (lcm-cpp's member-function
 * callbacks crash under UBSan's vptr check, which CI runs). Single-threaded like LCM itself.
 *
 * Overload: LCM keeps at most a subscription's queue capacity of received, unhandled messages and
 * drops the rest without a word (its default is 30). Every subscription here holds
 * `queue_capacity` messages (the apps' --queue-capacity, default 1000), and the drops are
 * counted: beside each subscription a counting one on the same channel holds
 * kDropCountFactor times as many; LCM delivers a message to every subscription that had room, so
 * a message the counter saw and the handler did not was dropped by the handler's queue
 * (dropped()). A burst beyond even the counter's room, and datagrams the kernel drops before LCM
 * (a UDP receive buffer too small for the burst: udpm's recv_buf_size), are not seen by anyone
 * (docs/lcm.md).
 */
#ifndef TDO_LCM_BUS_H
#define TDO_LCM_BUS_H

#include <lcm/lcm.h>

#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace tdo_lcm {

class Bus {
 public:
  /** Handler of raw message bytes; `channel` is the channel it arrived on. */
  using Handler =
      std::function<void(const void* data, std::size_t size, const std::string& channel)>;

  /** Messages each subscription queue holds by default (the apps' --queue-capacity). */
  static constexpr int kDefaultQueueCapacity = 1000;
  /** The counting subscription of a channel holds this many times the queue capacity. */
  static constexpr int kDropCountFactor = 4;

  /**
   * Connect to `url` (memq://, udpm://..., file://LOG?speed=0); check good(). A udpm:// URL
   * without recv_buf_size gets url.h's kRecvBufBytes.
   * @param queue_capacity messages each subscription queue holds (>= 1; smaller values: 1)
   */
  explicit Bus(const std::string& url, int queue_capacity = kDefaultQueueCapacity);
  ~Bus();
  Bus(const Bus&) = delete;
  Bus& operator=(const Bus&) = delete;

  /** @return true when LCM started. */
  bool good() const { return lcm_ != nullptr; }

  /** @brief Call `fn` for each message on `channel` (an exact name). @return false on failure. */
  bool subscribe(const std::string& channel, Handler fn);

  /** @brief Publish raw bytes. @return false on failure. */
  bool publish_raw(const std::string& channel, const void* data, std::size_t size);

  /** @brief Encode and publish a generated message. @return false when it cannot be encoded. */
  template <class Msg>
  bool publish(const std::string& channel, const Msg& m) {
    const int size = m.getEncodedSize();
    if (size <= 0) return false;
    buf_.resize(static_cast<std::size_t>(size));
    if (m.encode(buf_.data(), 0, size) != size) return false;
    return publish_raw(channel, buf_.data(), buf_.size());
  }

  /**
   * @brief Wait up to `timeout_ms` for one message and dispatch it.
   * @return > 0 handled, 0 timed out, < 0 error (also when a signal interrupted the wait).
   */
  int handle_timeout(int timeout_ms);

  /** @return the C instance (for lcm_* calls not wrapped here). */
  lcm_t* raw() { return lcm_; }

  /** @return messages each subscription queue holds. */
  int queue_capacity() const { return capacity_; }

  /** @return messages the subscription queues dropped so far, over every subscription. */
  int64_t dropped() const;

  /** @return messages received and not yet handled (the longest counting queue). */
  int queued() const;

 private:
  struct Sub {
    Handler fn;
    lcm_subscription_t* sub = nullptr;
    lcm_subscription_t* counter = nullptr;  // same channel, kDropCountFactor x the capacity
    int64_t arrived = 0;                    // messages the counting subscription saw
    int64_t handled = 0;                    // messages the handler got
  };
  static void on_message(const lcm_recv_buf_t* rbuf, const char* channel, void* user);
  static void on_arrival(const lcm_recv_buf_t* rbuf, const char* channel, void* user);
  int capacity_;
  lcm_t* lcm_ = nullptr;
  std::vector<std::unique_ptr<Sub>> subs_;
  std::vector<uint8_t> buf_;  // encode buffer, reused
};

}  // namespace tdo_lcm

#endif  // TDO_LCM_BUS_H
