// Allocation-free structural check of an encoded LCM message, driven by the generated C type info.
#include "tdo_lcm/wire.h"

#include <cstdint>
#include <cstring>
#include <vector>

namespace tdo_lcm {
namespace {

uint64_t read_be(const uint8_t* p, std::size_t n) {
  uint64_t v = 0;
  for (std::size_t i = 0; i < n; ++i) v = (v << 8) | p[i];
  return v;
}

/** Bytes of one element on the wire; 0 for strings and nested types. */
std::size_t element_bytes(lcm_field_type_t t) {
  switch (t) {
    case LCM_FIELD_INT8_T:
    case LCM_FIELD_BYTE:
    case LCM_FIELD_BOOLEAN:
      return 1;
    case LCM_FIELD_INT16_T:
      return 2;
    case LCM_FIELD_INT32_T:
    case LCM_FIELD_FLOAT:
      return 4;
    case LCM_FIELD_INT64_T:
    case LCM_FIELD_DOUBLE:
      return 8;
    default:
      return 0;
  }
}

/** Store a decoded integer scalar into the scratch struct, so later counts read it. */
void store_integer(const lcm_field_t& f, uint64_t raw) {
  switch (f.type) {
    case LCM_FIELD_INT8_T:
    case LCM_FIELD_BYTE:
    case LCM_FIELD_BOOLEAN: {
      const uint8_t v = static_cast<uint8_t>(raw);
      std::memcpy(f.data, &v, 1);
      break;
    }
    case LCM_FIELD_INT16_T: {
      const uint16_t v = static_cast<uint16_t>(raw);
      std::memcpy(f.data, &v, 2);
      break;
    }
    case LCM_FIELD_INT32_T: {
      const uint32_t v = static_cast<uint32_t>(raw);
      std::memcpy(f.data, &v, 4);
      break;
    }
    case LCM_FIELD_INT64_T:
      std::memcpy(f.data, &raw, 8);
      break;
    default:  // floating-point scalars are never counts
      break;
  }
}

}  // namespace

Check wire_check(const lcm_type_info_t* info, const void* data, std::size_t size) {
  if (info == nullptr || (data == nullptr && size > 0))
    return fail(Reason::decode_error, "no type info or no data");
  const uint8_t* buf = static_cast<const uint8_t*>(data);
  if (size < 8) return fail(Reason::truncated, std::to_string(size) + " bytes, no fingerprint");
  const uint64_t hash = read_be(buf, 8);
  if (hash != static_cast<uint64_t>(info->get_hash()))
    return fail(Reason::bad_fingerprint, "fingerprint does not match the expected type");

  // The generated get_field reads variable dimensions from the struct, so scalars are decoded into
  // a zeroed scratch struct as the walk passes them. Arrays are skipped, never stored.
  const int struct_bytes = info->struct_size();
  std::vector<uint64_t> scratch((static_cast<std::size_t>(struct_bytes) + 7u) / 8u + 1u, 0u);
  void* p = scratch.data();
  std::size_t pos = 8;
  const int fields = info->num_fields();
  for (int i = 0; i < fields; ++i) {
    lcm_field_t f;
    std::memset(&f, 0, sizeof(f));
    if (info->get_field(p, i, &f) != 0) return fail(Reason::decode_error, "no type info");
    uint64_t count = 1;
    for (int d = 0; d < f.num_dim; ++d) {
      if (f.dim_size[d] < 0)
        return fail(Reason::negative_count,
                    std::string(f.name) + ": count " + std::to_string(f.dim_size[d]));
      count *= static_cast<uint64_t>(f.dim_size[d]);
      if (count > size) {  // every element takes at least one byte
        return fail(Reason::truncated, std::string(f.name) + ": " + std::to_string(count) +
                                           " elements in a message of " + std::to_string(size) +
                                           " bytes");
      }
    }
    if (f.type == LCM_FIELD_STRING) {
      for (uint64_t e = 0; e < count; ++e) {
        if (size - pos < 4) return fail(Reason::truncated, std::string(f.name) + ": no length");
        const uint64_t len = read_be(buf + pos, 4);
        pos += 4;
        if (len == 0 || len > 0x7FFFFFFFu)
          return fail(Reason::bad_string, std::string(f.name) + ": bad string length");
        if (len > size - pos) return fail(Reason::truncated, std::string(f.name) + ": string");
        if (buf[pos + len - 1] != 0)
          return fail(Reason::bad_string, std::string(f.name) + ": string without its zero");
        pos += static_cast<std::size_t>(len);
      }
      continue;
    }
    const std::size_t elem = element_bytes(f.type);
    if (elem == 0) return fail(Reason::decode_error, std::string(f.name) + ": nested type");
    const uint64_t bytes = count * elem;
    if (bytes > size - pos)
      return fail(Reason::truncated, std::string(f.name) + ": needs " + std::to_string(bytes) +
                                         " bytes, " + std::to_string(size - pos) + " left");
    if (f.num_dim == 0) store_integer(f, read_be(buf + pos, elem));
    pos += static_cast<std::size_t>(bytes);
  }
  if (pos != size)
    return fail(Reason::trailing_bytes, std::to_string(size - pos) + " bytes after the message");
  return {};
}

}  // namespace tdo_lcm
