/**
 * @file url.h
 * @brief LCM URLs of the apps: the default one and the receive buffer every udpm:// URL gets.
 *
 * A trajectory answer with samples is ~280 kB and a map message up to a few hundred kB; LCM sends
 * them as many UDP fragments, which the kernel drops once the socket's receive buffer (212 kB by
 * default on Linux) is full. So every app asks for kRecvBufBytes unless the URL names its own
 * recv_buf_size. The kernel caps the request at net.core.rmem_max (raise it with
 * `sysctl -w net.core.rmem_max=4194304` where it is lower).
 */
#ifndef TDO_LCM_URL_H
#define TDO_LCM_URL_H

#include <string>

namespace tdo_lcm {

/** Receive buffer (bytes) the apps ask for on UDP multicast. */
inline constexpr long kRecvBufBytes = 4194304;

/**
 * @return `url` with "recv_buf_size=kRecvBufBytes" added when it is a udpm:// URL without a
 *         recv_buf_size option; any other URL unchanged.
 */
std::string with_recv_buf(const std::string& url);

}  // namespace tdo_lcm

#endif  // TDO_LCM_URL_H
