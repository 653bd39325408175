// tdo-bench-scale --load: map loading against the map format's own reader, in one process.
// Host-side bench code (allocates, reads files, links the OctoMap library).
#ifndef TDO_TOOLS_BENCH_SCALE_LOAD_H
#define TDO_TOOLS_BENCH_SCALE_LOAD_H

#include <cstdint>
#include <vector>

#include "scale_workloads.h"

namespace tdo_bench {

/**
 * @brief Time the loading of every OcTree and MovingAI map of `workloads` (each file once,
 * `.tdomap` maps skipped), `repeat` times, interleaved, and print one table row per map.
 *
 * Per repetition: the baseline is the reader of the format alone (OcTree: the OctoMap library's
 * OcTree::readBinary / AbstractOcTree::read of the file; `.3dmap`: tdo_io::load_map, which is the
 * text parse into a voxel list); tdo's load is tdo_io::load_map (for OcTrees: the check, the
 * OctoMap read and the voxelization) plus tdo_io::load_into (tdo_grid_reset, the voxels,
 * tdo_grid_finish at the workload's clearance) into a grid initialised before the timing.
 * Medians of the repetitions; the ratios are tdo's work beyond the baseline over the baseline
 * ("voxelization") and tdo's whole load over the baseline.
 * @return 0, or 2 after a message on stderr (unreadable map, failed grid).
 */
int run_load_bench(const std::vector<Workload>& workloads, uint64_t repeat);

}  // namespace tdo_bench

#endif  // TDO_TOOLS_BENCH_SCALE_LOAD_H
