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
 * Per repetition: the baseline is the OctoMap library reading the same tree (OcTree: its
 * OcTree::readBinary / AbstractOcTree::read of the map file; `.3dmap`: readBinary of the same map
 * as a tree, every voxel of the declared box a known leaf, the listed ones occupied and the rest
 * free, written once to a temporary .bt file); for `.3dmap` also, for context, OctoMap reading
 * the occupied voxels alone as a tree (in memory). tdo's load is tdo_io::load_map (for OcTrees:
 * the check, the OctoMap read and the voxelization; for `.3dmap` the parse) plus
 * tdo_io::load_into (tdo_grid_reset, the voxels, tdo_grid_finish at the workload's clearance) into
 * a grid initialised before the timing; after it, untimed as load, tdo_grid_prepare (the legal
 * steps and the distance field, which the first search and collision query build otherwise).
 * Medians of the repetitions; the ratios are tdo's work beyond the format's own read
 * ("voxelization": OcTree minus OctoMap's read of the file, `.3dmap` minus the parse) over the
 * baseline, tdo's whole load over the baseline, and for `.3dmap` over the occupied-only tree.
 * Goal lines: OcTrees voxelization / baseline, `.3dmap` whole load / baseline (issue 19: <= 2).
 * @return 0, or 2 after a message on stderr (unreadable map, failed grid).
 */
int run_load_bench(const std::vector<Workload>& workloads, uint64_t repeat);

}  // namespace tdo_bench

#endif  // TDO_TOOLS_BENCH_SCALE_LOAD_H
