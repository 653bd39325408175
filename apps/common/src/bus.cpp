// One LCM instance on the C API (bus.h).
#include "tdo_lcm/bus.h"

#include <algorithm>
#include <cstdint>
#include <utility>

#include "tdo_lcm/url.h"

namespace tdo_lcm {
namespace {

/** LCM subscribes by regular expression; escape everything but letters, digits and '_'. */
std::string exact(const std::string& channel) {
  std::string re;
  for (char ch : channel) {
    const bool plain = (ch >= 'a' && ch <= 'z') || (ch >= 'A' && ch <= 'Z') ||
                       (ch >= '0' && ch <= '9') || ch == '_';
    if (!plain) re.push_back('\\');
    re.push_back(ch);
  }
  return re;
}

}  // namespace

// udpm:// URLs get a receive buffer that fits the largest messages (url.h).
Bus::Bus(const std::string& url, int queue_capacity)
    : capacity_(std::clamp(queue_capacity, 1, INT32_MAX / kDropCountFactor)),
      lcm_(lcm_create(with_recv_buf(url).c_str())) {}

Bus::~Bus() {
  if (lcm_ == nullptr) return;
  for (auto& s : subs_) {
    if (s->sub != nullptr) lcm_unsubscribe(lcm_, s->sub);
    if (s->counter != nullptr) lcm_unsubscribe(lcm_, s->counter);
  }
  lcm_destroy(lcm_);
}

void Bus::on_arrival(const lcm_recv_buf_t* /*rbuf*/, const char* /*channel*/, void* user) {
  ++static_cast<Sub*>(user)->arrived;
}

void Bus::on_message(const lcm_recv_buf_t* rbuf, const char* channel, void* user) {
  Sub* s = static_cast<Sub*>(user);
  ++s->handled;
  s->fn(rbuf->data, rbuf->data_size, std::string(channel != nullptr ? channel : ""));
}

bool Bus::subscribe(const std::string& channel, Handler fn) {
  if (lcm_ == nullptr || !fn) return false;
  auto s = std::make_unique<Sub>();
  s->fn = std::move(fn);
  // The counter first: LCM calls a channel's handlers in the order they subscribed.
  s->counter = lcm_subscribe(lcm_, exact(channel).c_str(), &Bus::on_arrival, s.get());
  s->sub = lcm_subscribe(lcm_, exact(channel).c_str(), &Bus::on_message, s.get());
  if (s->counter == nullptr || s->sub == nullptr ||
      lcm_subscription_set_queue_capacity(s->counter, capacity_ * kDropCountFactor) != 0 ||
      lcm_subscription_set_queue_capacity(s->sub, capacity_) != 0) {
    if (s->counter != nullptr) lcm_unsubscribe(lcm_, s->counter);
    if (s->sub != nullptr) lcm_unsubscribe(lcm_, s->sub);
    return false;
  }
  subs_.push_back(std::move(s));
  return true;
}

int Bus::queued() const {
  int n = 0;
  for (const auto& s : subs_) n = std::max(n, lcm_subscription_get_queue_size(s->counter));
  return n;
}

int64_t Bus::dropped() const {
  int64_t n = 0;
  for (const auto& s : subs_) n += std::max<int64_t>(0, s->arrived - s->handled);
  return n;
}

bool Bus::publish_raw(const std::string& channel, const void* data, std::size_t size) {
  if (lcm_ == nullptr || size > 0x7FFFFFFFu) return false;
  return lcm_publish(lcm_, channel.c_str(), data, static_cast<unsigned int>(size)) == 0;
}

int Bus::handle_timeout(int timeout_ms) {
  if (lcm_ == nullptr) return -1;
  return lcm_handle_timeout(lcm_, timeout_ms);
}

}  // namespace tdo_lcm
