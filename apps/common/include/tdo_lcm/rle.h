/**
 * @file rle.h
 * @brief Run-length encoding of voxel occupancy (map_t.runs).
 *
 * Voxels in x-fastest order (index i + nx*(j + ny*k)); runs alternate free, occupied, free, ...
 * starting with a free run; zero runs only first (voxel 0 occupied) or between the parts of a run
 * longer than INT32_MAX. No runs at all means every voxel is free.
 */
#ifndef TDO_LCM_RLE_H
#define TDO_LCM_RLE_H

#include <cstdint>
#include <vector>

#include "tdo_lcm/check.h"

namespace tdo_lcm {

/** Incremental encoder: push voxels in order, then take the runs. */
class RleEncoder {
 public:
  /** Append the next voxel. */
  void push(bool occupied);
  /** Append `count` voxels of the same state. */
  void push_run(bool occupied, uint64_t count);
  /** @return the runs so far (the encoder can go on afterwards). */
  std::vector<int32_t> runs() const;
  /** @return voxels pushed. */
  uint64_t voxels() const { return voxels_; }

 private:
  std::vector<uint64_t> runs_;  // alternating free, occupied, ... (first free, may be 0)
  uint64_t voxels_ = 0;
};

/** @return runs encoding `occupancy` (one entry per voxel, non-zero = occupied). */
std::vector<int32_t> rle_encode(const std::vector<uint8_t>& occupancy);

/**
 * @brief Check that `runs` describe exactly `n_voxels` voxels.
 * @param[out] n_occupied occupied voxels (may be null)
 * @return ok, out_of_range (a negative run) or rle_mismatch (the runs do not add up).
 */
Check rle_check(const std::vector<int32_t>& runs, uint64_t n_voxels, uint64_t* n_occupied);

/**
 * @brief Call `fn(index)` for every occupied voxel index, in increasing order. Runs must have
 *        passed rle_check. Stops early and returns false when fn returns false.
 */
template <class Fn>
bool rle_for_each_occupied(const std::vector<int32_t>& runs, Fn&& fn) {
  uint64_t index = 0;
  for (std::size_t r = 0; r < runs.size(); ++r) {
    const uint64_t len = runs[r] > 0 ? static_cast<uint64_t>(runs[r]) : 0u;
    if (r % 2 == 1) {
      for (uint64_t e = 0; e < len; ++e)
        if (!fn(index + e)) return false;
    }
    index += len;
  }
  return true;
}

/** @return occupancy (one byte per voxel) decoded from checked runs of `n_voxels` voxels. */
std::vector<uint8_t> rle_decode(const std::vector<int32_t>& runs, uint64_t n_voxels);

}  // namespace tdo_lcm

#endif  // TDO_LCM_RLE_H
