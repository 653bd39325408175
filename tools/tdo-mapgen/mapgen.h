/**
 * @file mapgen.h
 * @brief Benchmark map generator behind tdo-mapgen: the six maps of docs/design.md s.9 and seeded
 * random column maps, byte-reproducible from the seed on every platform, checked solvable with
 *        libtdo. Host tool code (exceptions and allocation allowed); not part of libtdo.
 *
 * Reproducibility: all randomness comes from Rng (xoshiro256** seeded by splitmix64), drawn as
 * integers; geometry is kept in integer decimetres (boxes) and tenths of millimetres (movers) and
 * printed with integer arithmetic, so the text never depends on the standard library's
 * distributions or on printf rounding.
 */
#ifndef TDO_MAPGEN_MAPGEN_H
#define TDO_MAPGEN_MAPGEN_H

#include <cstdint>
#include <string>
#include <vector>

#include "tdo/types.h"

namespace tdo_mapgen {

/** One step of splitmix64 (Vigna): advances `*state` and returns the next output. */
uint64_t splitmix64(uint64_t* state);

/** xoshiro256** (Blackman and Vigna), seeded from (seed, stream) through splitmix64. */
class Rng {
 public:
  Rng(uint64_t seed, uint64_t stream);
  /** Next 64 random bits. */
  uint64_t next();
  /** Uniform integer in [0, n), unbiased (rejection); n > 0. */
  uint64_t below(uint64_t n);
  /** Uniform integer in [lo, hi]; lo <= hi. */
  int64_t range(int64_t lo, int64_t hi);

 private:
  uint64_t s_[4];
};

/** Streams are numbered per purpose so that, e.g., adding movers never changes the columns. */
constexpr uint64_t kMoverStreamBase = 0x4D4F564552000000ull; /**< "MOVER" tag, + draw stream */

/** An obstacle box in integer decimetres (exact in the text and at 1 m voxelisation). */
struct BoxDm {
  int32_t lo[3]; /**< dm, world frame, minimum corner */
  int32_t hi[3]; /**< dm, world frame, maximum corner (> lo on every axis) */
};

/** A moving sphere with constant velocity (reflected at the bounds by whoever simulates it). */
struct MoverOut {
  int id;           /**< 1-based identifier */
  int64_t pos[3];   /**< 0.1 mm, world frame, position at t = 0 */
  int32_t vel[3];   /**< mm/s, world frame */
  int32_t radius;   /**< mm */
  tdo_vec3 cross;   /**< m, world frame, the route point it passes through */
  double t_cross;   /**< s, when its centre passes `cross` */
  double route_arc; /**< m, arc length of `cross` along the route from the start */
  bool
      time_clipped; /**< crossing earlier than the nominal UAV arrival (the bounds were too near) */
};

/** How the static obstacles are laid out. */
enum class Layout {
  Hand,     /**< Map1: fixed walls and columns */
  Columns,  /**< random columns standing on the ground */
  Corridors /**< Map4: walls with doors forming corridors, pillars and beams inside */
};

/** Everything that determines a generated map. */
struct Params {
  std::string name;                           /**< "map1".."map6", empty for --random */
  Layout layout = Layout::Columns;            /**< obstacle layout */
  int32_t size[3] = {20, 20, 20};             /**< m, whole metres, bounds are [0, size] */
  int32_t resolution_mm = 1000;               /**< mm per voxel edge (the map's `resolution`) */
  uint32_t columns = 0;                       /**< obstacles to draw (Columns layout) */
  int32_t footprint_dm[2] = {10, 30};         /**< dm, min and max column footprint edge */
  uint64_t seed = 1;                          /**< random seed */
  uint32_t movers = 0;                        /**< moving spheres */
  int32_t mover_speed_mm[2] = {500, 1500};    /**< mm/s, min and max mover speed */
  int32_t mover_radius_mm[2] = {500, 1000};   /**< mm, min and max mover radius */
  int64_t start[3] = {20000, 20000, 30000};   /**< 0.1 mm, default query start */
  int64_t goal[3] = {190000, 190000, 100000}; /**< 0.1 mm, default query goal */
  int32_t margin_mm = 1500;                   /**< mm kept free of obstacles around start, goal */
  int32_t clearance_mm = 500;                 /**< mm, clearance of the solvability check */
  int32_t route_speed_mm = 2000; /**< mm/s, nominal UAV speed that times the mover crossings */
  uint32_t max_streams = 64;     /**< draws tried before giving up */
};

/**
 * @brief Parameters of one of the paper's maps.
 * @param name "map1" .. "map6"
 * @return false for an unknown name.
 */
bool preset(const std::string& name, Params* out);

/** The names preset() accepts, in order. */
const std::vector<std::string>& preset_names();

/**
 * @brief Check the parameters of a --random map (sizes, ranges, start/goal inside the bounds).
 * @return empty string when fine, else a message naming the option.
 */
std::string validate(const Params& p);

/**
 * @brief The command line that regenerates a map with these parameters (written into its header):
 *        `--map NAME -o maps/NAME.tdomap` for the presets, the full `--random ...` option list with
 *        `-o FILE` otherwise, so the text never depends on where the file is written.
 */
std::string regenerate_command(const Params& p);

/** Solvability and statistics of a map, from libtdo. */
struct Check {
  bool solved = false;         /**< bidirectional search found a path */
  int status = 0;              /**< tdo_status of the search */
  double length = 0.0;         /**< m, optimal grid path cost (voxel centres), when solved */
  uint64_t voxels = 0;         /**< nx*ny*nz */
  uint64_t blocked = 0;        /**< voxels blocked at the clearance */
  uint64_t occupied = 0;       /**< voxels intersecting obstacles */
  std::size_t boxes = 0;       /**< obstacle boxes in the file */
  std::size_t cubes = 0;       /**< occupied voxels in the file (voxel maps, OcTrees) */
  std::vector<tdo_vec3> route; /**< m, an independent shortest route (own A* over the blocked
                                    voxels), exact start and goal at the ends; when asked */
  double route_length = 0.0;   /**< m, cost of `route` over voxel centres */
  int32_t dims[3] = {0, 0, 0}; /**< grid size in voxels */
  double res = 0.0;            /**< m per voxel */
};

/**
 * @brief Load `path` with tdo_io, build a libtdo planner, finish the grid at `clearance` and run
 * the bidirectional search from start to goal (the map's own when `start`/`goal` are null).
 * @param resolution m, voxel size for OcTrees (0 = the tree's)
 * @param want_route also compute `route` with the generator's own A* (cross-check and movers)
 * @return false with `error` on unreadable input or a planner setup failure; an unsolvable query is
 *         `true` with `solved = false`.
 */
bool check_map(const std::string& path, double clearance, const tdo_vec3* start,
               const tdo_vec3* goal, double resolution, bool want_route, Check* out,
               std::string* error);

/** A generated map. */
struct Result {
  std::string text;             /**< the .tdomap file */
  uint64_t stream = 0;          /**< draw stream that was solvable */
  std::vector<BoxDm> boxes;     /**< static obstacles */
  std::vector<MoverOut> movers; /**< moving spheres */
  Check check;                  /**< libtdo check of the static map */
};

/**
 * @brief Generate a map: draw streams 0, 1, ... until libtdo solves it, then add the movers.
 * @param scratch_path file the candidate is written to and loaded from for the check, removed
 *        afterwards (".tdomap" is appended unless it ends so)
 * @return false with `error` when no stream in max_streams is solvable or a check fails.
 */
bool generate(const Params& p, const std::string& scratch_path, Result* out, std::string* error);

/** Decimal text of `v * 10^-decimals` with trailing zeros (and a bare point) removed. */
std::string fixed_text(int64_t v, int decimals);

}  // namespace tdo_mapgen

#endif  // TDO_MAPGEN_MAPGEN_H
