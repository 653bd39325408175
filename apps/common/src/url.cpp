// LCM URLs of the apps (url.h).
#include "tdo_lcm/url.h"

namespace tdo_lcm {

std::string with_recv_buf(const std::string& url) {
  if (url.rfind("udpm://", 0) != 0 || url.find("recv_buf_size=") != std::string::npos) return url;
  const char sep = url.find('?') == std::string::npos ? '?' : '&';
  return url + sep + "recv_buf_size=" + std::to_string(kRecvBufBytes);
}

}  // namespace tdo_lcm
