/**
 * @file bench.h
 * @brief Running planners over map sets and aggregating the runs into the paper's tables
 *        (tdo-bench, tdo-tune). Host code.
 */
#ifndef TDO_BENCH_BENCH_H
#define TDO_BENCH_BENCH_H

#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "baselines.h"
#include "tdo_io/map_io.h"

namespace tdo_bench {

/** One query on one map of a set. */
struct Query {
  std::string set;  /**< "paper", "random", "forest" */
  std::string map;  /**< map name (map1, random_3, forest0 ...) */
  int index = 0;    /**< query number within the map (forest trial number) */
  tdo_vec3 start{}; /**< m */
  tdo_vec3 goal{};  /**< m */
};

/** A loaded map and its environment (shared by every planner on it). */
struct MapCase {
  std::string set;
  std::string name;
  std::string file; /**< the map file (for the plots) */
  tdo_io::Map map;
  std::unique_ptr<tdo_baselines::Environment> env;
  std::vector<Query> queries;
};

/** One planner run. */
struct Run {
  Query q;
  std::string planner;
  uint64_t seed = 0;
  tdo_baselines::PlanResult r;
};

/**
 * @brief Load a map file into a case with an Environment at `clearance` (m); one query, the map's
 *        own start and goal, when it has them. node_cap: search states per direction (0 = all).
 */
bool load_case(const std::string& set, const std::string& name, const std::string& file,
               double clearance, uint32_t node_cap, MapCase* out, std::string* error);

/** Parameters of the random maps (tdo-mapgen --random). */
struct RandomSpec {
  int32_t size[3] = {40, 40, 20}; /**< m */
  uint32_t columns = 250;         /**< columns, footprint 1-3 m */
  uint64_t seed0 = 1000;          /**< map i has seed seed0 + i */
};

/**
 * @brief Generate random map `index` with tdo_mapgen (solvable at 0.5 m by construction), write it
 *        to DIR/random_<index>.tdomap and load it as a case (start (2,2,3), goal (X-1,Y-1,Z/2)).
 */
bool make_random_case(const RandomSpec& spec, int index, const std::string& dir, double clearance,
                      MapCase* out, std::string* error);

/**
 * @brief Read forest_gen's start_and_end.csv: queries of forest `map_id`, in file order.
 * @return false with `error` for an unreadable or malformed file.
 */
bool load_forest_queries(const std::string& csv, int map_id, std::vector<Query>* out,
                         std::string* error);

/** Median of `v` (NaN when empty). */
double median(std::vector<double> v);
/** Mean of `v` (NaN when empty). */
double mean(const std::vector<double>& v);

/** Aggregate of the runs of one planner on one map (or a group of maps). */
struct Agg {
  int runs = 0;
  int ok = 0;
  int feasible = 0;
  double success = 0.0;              /**< ok / runs */
  std::map<std::string, double> med; /**< median over successful runs of every metric column */
  double time_ms = 0.0;              /**< median plan time over all runs */
};

/** Metric columns in table order: key, header, printf format. */
struct Column {
  const char* key;
  const char* header;
  const char* format;
};
const std::vector<Column>& metric_columns();

/** The metric value of a successful result by column key. */
double metric(const tdo_baselines::PlanResult& r, const std::string& key);

/** Aggregate a list of runs. */
Agg aggregate(const std::vector<const Run*>& runs);

}  // namespace tdo_bench

#endif  // TDO_BENCH_BENCH_H
