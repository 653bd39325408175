// tdo-mapgen: generate the benchmark maps of docs/design.md s.9 and seeded random maps
// (byte-reproducible), and print statistics of any map. Exit 0 done, 1 no solvable map / unsolvable
// query, 2 bad input.
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "mapgen.h"
#include "tdo/status.h"
#include "tool_cli.h"

namespace {

using tdo_tool::BadInput;
using tdo_tool::kExitFailed;
using tdo_tool::kExitOk;

/** `v * scale` as an integer; it must be finite and on the grid of 1/scale (bad input if not). */
int64_t to_units(double v, double scale, const std::string& what, const char* step) {
  if (!std::isfinite(v)) throw BadInput{what + " must be finite"};
  const double x = v * scale;
  if (std::fabs(x) > 9e15) throw BadInput{what + " is out of range"};
  const double r = std::nearbyint(x);
  if (std::fabs(x - r) > 1e-6 * std::max(1.0, std::fabs(x)))
    throw BadInput{what + " must be given in steps of " + step};
  return static_cast<int64_t>(r);
}

std::string fmt(double v, const char* f = "%.6g") {
  char buf[64];
  std::snprintf(buf, sizeof buf, f, v);
  return buf;
}

std::string percent(uint64_t part, uint64_t whole) {
  return fmt(whole == 0 ? 0.0 : 100.0 * static_cast<double>(part) / static_cast<double>(whole),
             "%.2f") +
         " %";
}

bool write_atomic(const std::string& path, const std::string& text) {
  const std::string tmp = path + ".tmp" + std::to_string(static_cast<long>(::getpid()));
  std::FILE* f = std::fopen(tmp.c_str(), "wb");
  if (f == nullptr) return false;
  const bool ok = std::fwrite(text.data(), 1, text.size(), f) == text.size();
  if (std::fclose(f) != 0 || !ok) {
    std::remove(tmp.c_str());
    return false;
  }
  if (std::rename(tmp.c_str(), path.c_str()) != 0) {
    std::remove(tmp.c_str());
    return false;
  }
  return true;
}

/** The command line. */
struct Options {
  std::string map_name;
  bool random = false;
  std::string output;
  std::string stats_path;
  std::vector<int64_t> size;
  long long columns = 0;
  std::vector<double> footprint;
  uint64_t seed = 1;
  long long movers = 0;
  std::vector<double> mover_speed;
  std::vector<double> mover_radius;
  std::vector<double> start;
  std::vector<double> goal;
  double resolution = 0.0;
  double margin = 1.5;
  double clearance = 0.5;
  long long max_streams = 64;
  bool columns_given = false;
  bool resolution_given = false;
};

/** Declares the options on `app`, writing into `o`, with their exclusions. */
void add_options(CLI::App& app, Options& o) {
  auto* o_map = app.add_option("--map", o.map_name, "one of the paper's maps: map1 .. map6");
  auto* o_random =
      app.add_flag("--random", o.random, "a random column map (needs --size --columns)");
  auto* o_stats = app.add_option("--stats", o.stats_path,
                                 "print statistics of a map file (.tdomap, .3dmap, .bt, .ot): "
                                 "voxels, blocked fraction, bidirectional path length");
  app.add_option("-o,--output", o.output, "output .tdomap file");
  auto* o_size =
      app.add_option("--size", o.size, "X Y Z, whole metres (bounds [0, X] x ...)")->expected(3);
  auto* o_columns = app.add_option("--columns", o.columns, "number of columns");
  auto* o_foot = app.add_option("--footprint", o.footprint, "MIN MAX column edge, m (default 1 3)")
                     ->expected(2);
  auto* o_seed = app.add_option("--seed", o.seed, "random seed (default 1)");
  auto* o_movers = app.add_option("--movers", o.movers, "moving spheres crossing the route");
  auto* o_mspeed =
      app.add_option("--mover-speed", o.mover_speed, "MIN MAX, m/s (default 0.5 1.5)")->expected(2);
  auto* o_mradius =
      app.add_option("--mover-radius", o.mover_radius, "MIN MAX, m (default 0.5 1)")->expected(2);
  auto* o_start = app.add_option("--start", o.start, "X Y Z, m (default 2 2 3)")->expected(3);
  auto* o_goal =
      app.add_option("--goal", o.goal, "X Y Z, m (default X-1 Y-1 Z/2 of --size)")->expected(3);
  auto* o_res = app.add_option("--resolution", o.resolution,
                               "m per voxel (default 1; with --stats: OcTree voxel size, default "
                               "the tree's)");
  auto* o_margin =
      app.add_option("--margin", o.margin, "m free around start and goal (default 1.5)");
  app.add_option("--clearance", o.clearance, "m, clearance of the solvability check (default 0.5)");
  auto* o_streams =
      app.add_option("--max-streams", o.max_streams, "draw streams tried before giving up (64)");
  for (auto* opt :
       {o_size, o_columns, o_foot, o_seed, o_movers, o_mspeed, o_mradius, o_margin, o_streams}) {
    opt->excludes(o_map);
    opt->excludes(o_stats);
  }
  o_map->excludes(o_random);
  o_map->excludes(o_stats);
  o_random->excludes(o_stats);
  o_start->excludes(o_map);
  o_goal->excludes(o_map);
  o_res->excludes(o_map);
}

/** --stats: prints the statistics of an existing map; exit 0 when its query is solved, else 1. */
int print_stats(const Options& o) {
  if (!o.output.empty()) throw BadInput{"--stats writes nothing: drop -o"};
  if (!std::isfinite(o.resolution) || o.resolution < 0.0)
    throw BadInput{"--resolution must be finite and >= 0"};
  tdo_vec3 s{};
  tdo_vec3 g{};
  if (!o.start.empty()) s = tdo_vec3{o.start[0], o.start[1], o.start[2]};
  if (!o.goal.empty()) g = tdo_vec3{o.goal[0], o.goal[1], o.goal[2]};
  for (double v : o.start)
    if (!std::isfinite(v)) throw BadInput{"--start must be finite"};
  for (double v : o.goal)
    if (!std::isfinite(v)) throw BadInput{"--goal must be finite"};
  tdo_mapgen::Check c;
  std::string err;
  if (!tdo_mapgen::check_map(o.stats_path, o.clearance, o.start.empty() ? nullptr : &s,
                             o.goal.empty() ? nullptr : &g, o.resolution, false, &c, &err)) {
    throw BadInput{err};
  }
  std::printf("map        %s\n", o.stats_path.c_str());
  std::printf("grid       %d x %d x %d voxels, res %s m\n", c.dims[0], c.dims[1], c.dims[2],
              fmt(c.res).c_str());
  std::printf("obstacles  %zu boxes, %zu voxels\n", c.boxes, c.cubes);
  std::printf("occupied   %llu voxels (%s)\n", static_cast<unsigned long long>(c.occupied),
              percent(c.occupied, c.voxels).c_str());
  std::printf("blocked    %llu voxels (%s) at clearance %s m\n",
              static_cast<unsigned long long>(c.blocked), percent(c.blocked, c.voxels).c_str(),
              fmt(o.clearance).c_str());
  std::printf("bidir      %s", tdo_status_str(static_cast<tdo_status>(c.status)));
  if (c.solved) std::printf(", length %.4f m", c.length);
  std::printf("\n");
  return c.solved ? kExitOk : kExitFailed;
}

/** The generator parameters of a --random map, checked (bad input if not). */
tdo_mapgen::Params random_params(const Options& o) {
  tdo_mapgen::Params p;
  if (o.size.empty()) throw BadInput{"--random needs --size X Y Z"};
  if (!o.columns_given) throw BadInput{"--random needs --columns N"};
  for (int a = 0; a < 3; ++a) {
    if (o.size[a] < 2 || o.size[a] > 10000)
      throw BadInput{"--size: each size must be a whole number of metres in [2, 10000]"};
    p.size[a] = static_cast<int32_t>(o.size[a]);
  }
  if (o.columns < 0 || o.columns > 1000000) throw BadInput{"--columns must be in [0, 1000000]"};
  p.columns = static_cast<uint32_t>(o.columns);
  p.seed = o.seed;
  if (!o.footprint.empty()) {
    p.footprint_dm[0] = static_cast<int32_t>(to_units(o.footprint[0], 10, "--footprint", "0.1 m"));
    p.footprint_dm[1] = static_cast<int32_t>(to_units(o.footprint[1], 10, "--footprint", "0.1 m"));
  }
  if (o.movers < 0 || o.movers > 10000) throw BadInput{"--movers must be in [0, 10000]"};
  p.movers = static_cast<uint32_t>(o.movers);
  if (!o.mover_speed.empty()) {
    for (int i = 0; i < 2; ++i)
      p.mover_speed_mm[i] =
          static_cast<int32_t>(to_units(o.mover_speed[i], 1000, "--mover-speed", "0.001 m/s"));
  }
  if (!o.mover_radius.empty()) {
    for (int i = 0; i < 2; ++i)
      p.mover_radius_mm[i] =
          static_cast<int32_t>(to_units(o.mover_radius[i], 1000, "--mover-radius", "0.001 m"));
  }
  const double dstart[3] = {2.0, 2.0, 3.0};
  const double dgoal[3] = {p.size[0] - 1.0, p.size[1] - 1.0, p.size[2] / 2.0};
  for (int a = 0; a < 3; ++a) {
    p.start[a] = to_units(o.start.empty() ? dstart[a] : o.start[a], 1e4, "--start", "0.0001 m");
    p.goal[a] = to_units(o.goal.empty() ? dgoal[a] : o.goal[a], 1e4, "--goal", "0.0001 m");
  }
  if (o.resolution_given)
    p.resolution_mm = static_cast<int32_t>(to_units(o.resolution, 1000, "--resolution", "1 mm"));
  p.margin_mm = static_cast<int32_t>(to_units(o.margin, 1000, "--margin", "1 mm"));
  if (o.max_streams < 1 || o.max_streams > 1000000)
    throw BadInput{"--max-streams must be in [1, 1000000]"};
  p.max_streams = static_cast<uint32_t>(o.max_streams);
  return p;
}

/** Generates the map of `p`, checks it solvable and writes it to o.output. */
int generate_map(const Options& o, const tdo_mapgen::Params& p) {
  tdo_mapgen::Result r;
  std::string err;
  const std::string scratch = o.output + ".check" + std::to_string(static_cast<long>(::getpid()));
  if (!tdo_mapgen::generate(p, scratch, &r, &err)) {
    std::fprintf(stderr, "tdo-mapgen: %s\n", err.c_str());
    return kExitFailed;
  }
  if (!write_atomic(o.output, r.text)) {
    std::fprintf(stderr, "tdo-mapgen: %s: cannot write\n", o.output.c_str());
    return kExitFailed;
  }
  std::printf(
      "%s: %zu boxes, %zu movers, stream %llu, blocked %s at clearance %s m, bidir length "
      "%.4f m\n",
      o.output.c_str(), r.boxes.size(), r.movers.size(), static_cast<unsigned long long>(r.stream),
      percent(r.check.blocked, r.check.voxels).c_str(), fmt(o.clearance).c_str(), r.check.length);
  return kExitOk;
}

int run(int argc, char** argv) {
  CLI::App app{
      "Generate the benchmark maps of docs/design.md s.9 (Map1-Map6) or seeded random column maps "
      "as "
      ".tdomap,\n"
      "byte-reproducible from the seed and checked solvable with libtdo (bidirectional search at\n"
      "--clearance); or print statistics of an existing map (--stats).\n"
      "Exit status: 0 done, 1 no solvable map (or --stats query unsolved), 2 bad input.",
      "tdo-mapgen"};
  Options o;
  add_options(app, o);
  const int parsed = tdo_tool::parse_args(app, argc, argv);
  if (parsed >= 0) return parsed;
  o.columns_given = app.count("--columns") > 0;
  o.resolution_given = app.count("--resolution") > 0;
  if (!std::isfinite(o.clearance) || o.clearance < 0.0)
    throw BadInput{"--clearance must be finite and >= 0"};
  if (!o.stats_path.empty()) return print_stats(o);

  if (o.map_name.empty() && !o.random)
    throw BadInput{"give --map NAME, --random ... or --stats FILE (see --help)"};
  if (o.output.empty()) throw BadInput{"-o FILE is required"};
  tdo_mapgen::Params p;
  if (!o.map_name.empty()) {
    if (!tdo_mapgen::preset(o.map_name, &p)) {
      throw BadInput{"--map: unknown map '" + o.map_name + "' (expected map1 .. map6)"};
    }
  } else {
    p = random_params(o);
  }
  p.clearance_mm = static_cast<int32_t>(to_units(o.clearance, 1000, "--clearance", "1 mm"));
  const std::string bad = tdo_mapgen::validate(p);
  if (!bad.empty()) throw BadInput{bad};
  return generate_map(o, p);
}

}  // namespace

int main(int argc, char** argv) { return tdo_tool::guarded_main("tdo-mapgen", run, argc, argv); }
