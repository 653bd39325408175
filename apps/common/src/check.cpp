// Names of the adapter reasons (stable: they are counted in heartbeats and sent in answers).
#include "tdo_lcm/check.h"

namespace tdo_lcm {

const char* reason_str(Reason reason) {
  switch (reason) {
    case Reason::ok:
      return "ok";
    case Reason::bad_fingerprint:
      return "bad_fingerprint";
    case Reason::truncated:
      return "truncated";
    case Reason::trailing_bytes:
      return "trailing_bytes";
    case Reason::negative_count:
      return "negative_count";
    case Reason::bad_string:
      return "bad_string";
    case Reason::decode_error:
      return "decode_error";
    case Reason::count_mismatch:
      return "count_mismatch";
    case Reason::non_finite:
      return "non_finite";
    case Reason::out_of_range:
      return "out_of_range";
    case Reason::bad_enum:
      return "bad_enum";
    case Reason::other_vehicle:
      return "other_vehicle";
    case Reason::map_capacity:
      return "map_capacity";
    case Reason::bad_encoding:
      return "bad_encoding";
    case Reason::unsupported_encoding:
      return "unsupported_encoding";
    case Reason::rle_mismatch:
      return "rle_mismatch";
    case Reason::grid_error:
      return "grid_error";
    case Reason::no_map:
      return "no_map";
    case Reason::unknown_map:
      return "unknown_map";
    case Reason::too_large:
      return "too_large";
    case Reason::no_plan:
      return "no_plan";
    case Reason::over_capacity:
      return "over_capacity";
    case Reason::library_error:
      return "library_error";
    case Reason::gap:
      return "gap";
    case Reason::stale_update:
      return "stale_update";
    case Reason::other_map:
      return "other_map";
    case Reason::contradictory:
      return "contradictory";
    case Reason::map_stale:
      return "map_stale";
  }
  return "unknown_reason";
}

}  // namespace tdo_lcm
