// Run-length encoding of voxel occupancy.
#include "tdo_lcm/rle.h"

#include <string>

namespace tdo_lcm {

void RleEncoder::push(bool occupied) { push_run(occupied, 1); }

void RleEncoder::push_run(bool occupied, uint64_t count) {
  if (count == 0) return;
  if (runs_.empty()) runs_.push_back(0);  // the first run is free
  const bool last_occupied = (runs_.size() % 2) == 0;
  if (last_occupied != occupied) runs_.push_back(0);
  runs_.back() += count;
  voxels_ += count;
}

std::vector<int32_t> RleEncoder::runs() const {
  constexpr uint64_t kMax = 0x7FFFFFFFu;
  std::vector<int32_t> out;
  out.reserve(runs_.size());
  for (std::size_t r = 0; r < runs_.size(); ++r) {
    uint64_t len = runs_[r];
    // A run longer than INT32_MAX becomes parts separated by zero runs of the other state.
    while (len > kMax) {
      out.push_back(static_cast<int32_t>(kMax));
      out.push_back(0);
      len -= kMax;
    }
    out.push_back(static_cast<int32_t>(len));
  }
  return out;
}

std::vector<int32_t> rle_encode(const std::vector<uint8_t>& occupancy) {
  RleEncoder enc;
  for (uint8_t v : occupancy) enc.push(v != 0);
  return enc.runs();
}

Check rle_check(const std::vector<int32_t>& runs, uint64_t n_voxels, uint64_t* n_occupied) {
  uint64_t total = 0;
  uint64_t occupied = 0;
  for (std::size_t r = 0; r < runs.size(); ++r) {
    if (runs[r] < 0)
      return fail(Reason::out_of_range,
                  "runs[" + std::to_string(r) + "] = " + std::to_string(runs[r]) + " < 0");
    total += static_cast<uint64_t>(runs[r]);
    if (r % 2 == 1) occupied += static_cast<uint64_t>(runs[r]);
  }
  if (!runs.empty() && total != n_voxels)
    return fail(Reason::rle_mismatch, "runs add up to " + std::to_string(total) +
                                          " voxels, the map has " + std::to_string(n_voxels));
  if (n_occupied != nullptr) *n_occupied = occupied;
  return {};
}

std::vector<uint8_t> rle_decode(const std::vector<int32_t>& runs, uint64_t n_voxels) {
  std::vector<uint8_t> occ(static_cast<std::size_t>(n_voxels), 0u);
  rle_for_each_occupied(runs, [&](uint64_t i) {
    if (i < n_voxels) occ[static_cast<std::size_t>(i)] = 1u;
    return true;
  });
  return occ;
}

}  // namespace tdo_lcm
