/**
 * @file wire.h
 * @brief Safe decoding of received LCM bytes.
 *
 * lcm-gen's decoders size their arrays from the counts on the wire before checking that the bytes
 * are there, so a corrupt count can make them allocate gigabytes or throw. wire_check walks the
 * encoded message with the type's generated C type info (always in step with the .lcm file),
 * checks the fingerprint, every count against the bytes left, every string, and the exact length,
 * without allocating. decode() runs it and only then the generated C++ decoder.
 */
#ifndef TDO_LCM_WIRE_H
#define TDO_LCM_WIRE_H

#include <lcm/lcm_coretypes.h>

#include <cstddef>
#include <cstdint>
#include <string>

#include "tdo_lcm/check.h"
#include "tdo_lcm/types.h"

namespace tdo_lcm {

/**
 * @brief Check that `size` bytes at `data` are one complete message of the type `info` describes.
 * @return ok, bad_fingerprint, truncated, trailing_bytes, negative_count or bad_string.
 */
Check wire_check(const lcm_type_info_t* info, const void* data, std::size_t size);

/**
 * @brief wire_check, then the generated C++ decoder (exceptions caught: decode_error).
 * @param[out] out the message (unspecified on failure)
 */
template <class Msg>
Check decode(const void* data, std::size_t size, Msg* out) {
  Check c = wire_check(TypeInfo<Msg>::get(), data, size);
  if (!c.ok()) return c;
  try {
    if (out->decode(data, 0, static_cast<int>(size)) != static_cast<int>(size))
      return fail(Reason::decode_error, std::string(Msg::getTypeName()) + ": decoder failed");
  } catch (...) {
    return fail(Reason::decode_error, std::string(Msg::getTypeName()) + ": decoder threw");
  }
  return {};
}

/**
 * @brief decode a map, then refuse it (other_vehicle) when it is for a vehicle other than
 *        `vehicle_id` (vehicle -1 in the map: for every vehicle).
 */
inline Check decode_map(const void* data, std::size_t size, int32_t vehicle_id, tdo::map_t* m) {
  Check c = decode(data, size, m);
  if (c.ok() && m->vehicle_id != -1 && m->vehicle_id != vehicle_id)
    c = fail(Reason::other_vehicle, "map for vehicle " + std::to_string(m->vehicle_id));
  return c;
}

}  // namespace tdo_lcm

#endif  // TDO_LCM_WIRE_H
