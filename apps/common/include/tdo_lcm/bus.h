/**
 * @file bus.h
 * @brief A small owner of one LCM instance on the C API: subscribe raw bytes, publish messages.
 *
 * The apps use this instead of lcm-cpp.hpp's templated subscriptions: the handlers get the raw
 * bytes (decoded with wire.h's checks, so bad messages are counted rather than dropped with a
 * print), and there is no cast of LCM's user data to a polymorphic type (lcm-cpp's member-function
 * callbacks crash under UBSan's vptr check, which CI runs). Single-threaded like LCM itself.
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

  /** Connect to `url` (memq://, udpm://..., file://LOG?speed=0); check good(). A udpm:// URL
   *  without recv_buf_size gets url.h's kRecvBufBytes. */
  explicit Bus(const std::string& url);
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

 private:
  struct Sub {
    Handler fn;
    lcm_subscription_t* sub = nullptr;
  };
  lcm_t* lcm_ = nullptr;
  std::vector<std::unique_ptr<Sub>> subs_;
  std::vector<uint8_t> buf_;  // encode buffer, reused
};

}  // namespace tdo_lcm

#endif  // TDO_LCM_BUS_H
