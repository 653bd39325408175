// One LCM instance on the C API (bus.h).
#include "tdo_lcm/bus.h"

#include <utility>

#include "tdo_lcm/url.h"

namespace tdo_lcm {
namespace {

void dispatch(const lcm_recv_buf_t* rbuf, const char* channel, void* user) {
  const auto* fn = static_cast<const Bus::Handler*>(user);
  (*fn)(rbuf->data, rbuf->data_size, std::string(channel != nullptr ? channel : ""));
}

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
Bus::Bus(const std::string& url) : lcm_(lcm_create(with_recv_buf(url).c_str())) {}

Bus::~Bus() {
  if (lcm_ == nullptr) return;
  for (auto& s : subs_)
    if (s->sub != nullptr) lcm_unsubscribe(lcm_, s->sub);
  lcm_destroy(lcm_);
}

bool Bus::subscribe(const std::string& channel, Handler fn) {
  if (lcm_ == nullptr || !fn) return false;
  auto s = std::make_unique<Sub>();
  s->fn = std::move(fn);
  s->sub = lcm_subscribe(lcm_, exact(channel).c_str(), dispatch, &s->fn);
  if (s->sub == nullptr) return false;
  subs_.push_back(std::move(s));
  return true;
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
