// tdo-tune: tune the parameters libtdo's table marks for tuning (tdo/params.h rows with a tune
// range: `tdo-plan --list-params`) of the tdo pipeline with NLopt on a training set of maps and
// check the result on a held-out set, beside the library's defaults (the paper's).
//
// Algorithm: NLOPT_LN_SBPLX (Rowan's Subplex: Nelder-Mead on subspaces), derivative-free and
// local. Why: the objective is a deterministic but piecewise-constant function of the parameters
// (turn counts and grid paths change in jumps), so methods that fit smooth models (BOBYQA, COBYLA)
// see zero or meaningless gradients between jumps; a simplex method with large initial steps keeps
// moving across the plateaus. Subplex is NLopt's recommended, more robust variant of Nelder-Mead.
// LN_NELDERMEAD and LN_BOBYQA are selectable for comparison (--algorithm).
//
// Objective (lower is better), over a set of M maps, p0 = the library's defaults:
//   J(p) = (1/M) sum_m [ T_m(p) / T_m(p0) + 0.05 * turns_m(p) + 1 * infeasible_m(p) ],
// with a term of 10 for a map where no path is found. T = flight time of the time-parameterised
// trajectory (it grows with length, with slow corners and with stop points), turns = interior
// waypoints of P2 deflecting more than 1 degree (docs/design.md s.6). One turn weighs like 5 % of
// the flight time. J(p0) = 1 + 0.05 * mean turns by construction.
//
// Parameters are optimised in normalised coordinates [0,1]^n over their rows' tune ranges (angles
// in degrees); initial step 0.25; at most --maxeval evaluations of J on the training set. Exit
// status 0 done, 2 bad input.
#include <CLI/CLI.hpp>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <nlopt.hpp>
#include <string>
#include <vector>

#include "baselines.h"
#include "bench.h"
#include "tdo/params.h"
#include "tool_cli.h"

namespace fs = std::filesystem;

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

using tdo_tool::BadInput;

constexpr double kDeg = 3.14159265358979323846 / 180.0;

std::string fmt_num(double v, const char* f) {
  char buf[64];
  std::snprintf(buf, sizeof buf, f, v);
  return buf;
}

std::string fmt(double v, const char* f) { return std::isnan(v) ? "-" : fmt_num(v, f); }

/** One tuned parameter: a row of tdo/params.h with a tune range, in the bench planner's units. */
struct Tuned {
  std::string name; /**< the row's name */
  std::string key;  /**< the bench planner's parameter: name, "_deg" for angles */
  std::string unit; /**< " deg" for angles, else "" */
  double lo, hi;    /**< tune range */
  double def;       /**< the library's default */
};

/** The rows with a tune range (tune_min < tune_max), in table order. */
std::vector<Tuned> tuned_rows() {
  std::vector<Tuned> v;
  for (uint32_t i = 0; i < tdo_param_count(); ++i) {
    const tdo_param_info& r = *tdo_param_at(i);
    if (!(r.tune_min < r.tune_max)) continue;
    const bool angle = std::string(r.unit) == "rad";
    const double s = angle ? 1.0 / kDeg : 1.0;
    // 12 digits: 45 degrees, not 45.000000000000007
    const auto shown = [s](double x) { return std::stod(fmt_num(x * s, "%.12g")); };
    v.push_back({r.name, std::string(r.name) + (angle ? "_deg" : ""), angle ? " deg" : "",
                 shown(r.tune_min), shown(r.tune_max), shown(r.def)});
  }
  return v;
}

struct MapEval {
  bool ok = false;
  bool feasible = false;
  double flight_time = kNaN;
  double turns = kNaN;
  double length = kNaN;
  double plan_ms = kNaN;
};

class Tuner {
 public:
  std::vector<Tuned> params = tuned_rows();
  std::vector<tdo_bench::MapCase>* train = nullptr;
  std::unique_ptr<tdo_baselines::Planner> tdo;
  std::vector<MapEval> ref_train;  // p0 on the training set
  std::vector<std::vector<double>> log;
  int evals = 0;

  std::vector<double> defaults() const {
    std::vector<double> p;
    for (const Tuned& t : params) p.push_back(t.def);
    return p;
  }

  std::vector<MapEval> run(std::vector<tdo_bench::MapCase>& cases, const std::vector<double>& p) {
    std::string err;
    for (std::size_t i = 0; i < params.size(); ++i)
      if (!tdo->set_param(params[i].key, p[i], &err)) throw BadInput{err};
    std::vector<MapEval> out;
    for (tdo_bench::MapCase& c : cases) {
      const tdo_bench::Query& q = c.queries.front();
      const tdo_baselines::PlanResult r = tdo->plan(*c.env, q.start, q.goal, 0);
      MapEval e;
      e.ok = r.ok;
      e.feasible = r.feasible;
      e.plan_ms = r.plan_time_ms;
      if (r.ok) {
        e.flight_time = r.has_trajectory ? r.metrics.flight_time_s : kNaN;
        e.turns = r.metrics.turns;
        e.length = r.metrics.length_m;
      }
      out.push_back(e);
    }
    return out;
  }

  /** Parameters from normalised coordinates u in [0,1]^n. */
  std::vector<double> denorm(const std::vector<double>& u) const {
    std::vector<double> p(params.size());
    for (std::size_t i = 0; i < params.size(); ++i)
      p[i] = params[i].lo + std::min(1.0, std::max(0.0, u[i])) * (params[i].hi - params[i].lo);
    return p;
  }

  static double objective(const std::vector<MapEval>& e, const std::vector<MapEval>& ref) {
    double s = 0.0;
    for (std::size_t i = 0; i < e.size(); ++i) {
      if (!e[i].ok || std::isnan(e[i].flight_time) || std::isnan(ref[i].flight_time) ||
          !(ref[i].flight_time > 0.0)) {
        s += 10.0;
        continue;
      }
      s += e[i].flight_time / ref[i].flight_time + 0.05 * e[i].turns + (e[i].feasible ? 0.0 : 1.0);
    }
    return e.empty() ? kNaN : s / static_cast<double>(e.size());
  }
};

double nlopt_objective(const std::vector<double>& u, std::vector<double>& /*grad*/, void* data) {
  auto* t = static_cast<Tuner*>(data);
  const std::vector<double> p = t->denorm(u);
  const double j = Tuner::objective(t->run(*t->train, p), t->ref_train);
  ++t->evals;
  std::vector<double> row = p;
  row.push_back(j);
  t->log.push_back(row);
  std::fprintf(stderr, "\r[tune] evaluation %d: J = %.5f   ", t->evals, j);
  return j;
}

void write_file(const fs::path& p, const std::string& text) {
  std::ofstream f(p);
  f << text;
  if (!f) throw BadInput{"cannot write " + p.string()};
}

/** The command line. */
struct Options {
  std::string out;
  std::string maps_dir = TDO_TUNE_MAPS_DIR;
  std::string heldout = "map1,map2,map3,map4,map5,map6";
  int train_random = 6;
  std::vector<int> size = {40, 40, 20};
  int columns = 250;
  int maxeval = 60;
  std::string algorithm = "sbplx";
  double clearance = 0.5;
  bool test = false;
};

/** The tuned rows' names, comma-separated, `last_sep` before the last. */
std::string names_text(const std::vector<Tuned>& params, const char* last_sep) {
  std::string s;
  for (std::size_t i = 0; i < params.size(); ++i)
    s += (i == 0 ? "" : i + 1 == params.size() ? last_sep : ", ") + params[i].name;
  return s;
}

/** Parse the command line (test mode's smaller defaults included). Returns -1 to go on, else an
 *  exit status (--help). */
int parse_options(int argc, char** argv, Options* o) {
  CLI::App app{"Tune " + names_text(tuned_rows(), " and ") +
                   " of tdo with NLopt (derivative-free) on random training maps; check on "
                   "held-out maps beside the library's defaults.",
               "tdo-tune"};
  app.add_option("--out", o->out, "output directory (created)")->required();
  app.add_option("--maps-dir", o->maps_dir, "the repository's maps/ directory")
      ->capture_default_str();
  app.add_option("--heldout", o->heldout, "held-out paper maps (comma list)")
      ->capture_default_str();
  app.add_option("--train-random", o->train_random,
                 "training maps (tdo-mapgen --random, seeds 2000..)")
      ->capture_default_str();
  app.add_option("--random-size", o->size, "X Y Z of the training maps, m")->expected(3);
  app.add_option("--random-columns", o->columns, "columns per training map")->capture_default_str();
  app.add_option("--maxeval", o->maxeval, "evaluation budget of the optimiser")
      ->capture_default_str();
  app.add_option("--algorithm", o->algorithm, "sbplx | neldermead | bobyqa")
      ->check(CLI::IsMember({"sbplx", "neldermead", "bobyqa"}))
      ->capture_default_str();
  app.add_option("--clearance", o->clearance, "m")->capture_default_str();
  app.add_flag("--test", o->test, "smoke test: 1 small training map, map1 held out, 8 evaluations");
  const int help = tdo_tool::parse_args(app, argc, argv);
  if (help >= 0) return help;
  if (o->test) {
    if (app.count("--heldout") == 0) o->heldout = "map1";
    if (app.count("--train-random") == 0) o->train_random = 1;
    if (app.count("--random-size") == 0) o->size = {16, 16, 8};
    if (app.count("--random-columns") == 0) o->columns = 25;
    if (app.count("--maxeval") == 0) o->maxeval = 8;
  }
  if (o->maxeval < 1 || o->maxeval > 100000) throw BadInput{"--maxeval must be in [1, 100000]"};
  if (o->train_random < 1) throw BadInput{"--train-random must be >= 1"};
  return -1;
}

/** The random training maps (written to OUT/maps) and the held-out paper maps. */
void load_cases(const Options& o, const fs::path& dir, std::vector<tdo_bench::MapCase>* train,
                std::vector<tdo_bench::MapCase>* held) {
  tdo_bench::RandomSpec spec;
  for (int a = 0; a < 3; ++a) spec.size[a] = o.size[a];
  spec.columns = static_cast<uint32_t>(o.columns);
  spec.seed0 = 2000;
  std::string err;
  for (int i = 0; i < o.train_random; ++i) {
    tdo_bench::MapCase c;
    if (!tdo_bench::make_random_case(spec, i, (dir / "maps").string(), o.clearance, &c, &err))
      throw BadInput{err};
    train->push_back(std::move(c));
  }
  std::string list = o.heldout + ",";
  for (std::size_t pos = 0, next; (next = list.find(',', pos)) != std::string::npos;
       pos = next + 1) {
    const std::string m = list.substr(pos, next - pos);
    if (m.empty()) continue;
    tdo_bench::MapCase c;
    if (!tdo_bench::load_case("paper", m, o.maps_dir + "/" + m + ".tdomap", o.clearance, 0, &c,
                              &err))
      throw BadInput{err};
    if (c.queries.empty()) throw BadInput{m + ": no start/goal"};
    held->push_back(std::move(c));
  }
}

/** The optimiser's run from the defaults; returns the best point found and NLopt's result. */
std::vector<double> optimise(const Options& o, Tuner* t, std::string* result) {
  const std::size_t n = t->params.size();
  const nlopt::algorithm alg = o.algorithm == "bobyqa"       ? nlopt::LN_BOBYQA
                               : o.algorithm == "neldermead" ? nlopt::LN_NELDERMEAD
                                                             : nlopt::LN_SBPLX;
  nlopt::opt opt(alg, static_cast<unsigned>(n));
  opt.set_lower_bounds(std::vector<double>(n, 0.0));
  opt.set_upper_bounds(std::vector<double>(n, 1.0));
  opt.set_min_objective(nlopt_objective, t);
  opt.set_maxeval(o.maxeval);
  opt.set_xtol_rel(1e-4);
  opt.set_initial_step(std::vector<double>(n, 0.25));
  std::vector<double> u(n);
  for (std::size_t i = 0; i < n; ++i) {
    const Tuned& p = t->params[i];
    u[i] = (p.def - p.lo) / (p.hi - p.lo);
  }
  double jbest = kNaN;
  *result = "ok";
  try {
    const nlopt::result r = opt.optimize(u, jbest);
    *result = std::to_string(static_cast<int>(r));
  } catch (const std::exception& e) {
    *result = std::string("stopped: ") + e.what();
  }
  std::fprintf(stderr, "\n");
  return t->denorm(u);
}

/** J of the defaults and of the tuned parameters on both sets, and the held-out maps' runs. */
struct Outcome {
  std::vector<double> best;
  std::string result;
  double j_train_default = kNaN, j_train_tuned = kNaN;
  double j_held_default = kNaN, j_held_tuned = kNaN;
  std::vector<MapEval> ref_held, tuned_held;
};

std::string evaluations_csv(const Tuner& t) {
  std::string csv = "evaluation";
  for (const Tuned& p : t.params) csv += "," + p.key;
  csv += ",J_train\n";
  for (std::size_t i = 0; i < t.log.size(); ++i) {
    csv += std::to_string(i + 1);
    for (double v : t.log[i]) csv += "," + fmt(v, "%.6g");
    csv += "\n";
  }
  return csv;
}

std::string tune_md(const Options& o, const Tuner& t, const Outcome& r,
                    const std::vector<tdo_bench::MapCase>& held) {
  std::string bounds;
  for (const Tuned& p : t.params)
    bounds += (bounds.empty() ? "" : ", ") + p.name + " [" + fmt(p.lo, "%g") + ", " +
              fmt(p.hi, "%g") + "]" + p.unit;
  std::string md = "### NLopt tuning of (" + names_text(t.params, ", ") + ")\n\n";
  md += "Algorithm NLOPT_LN_" +
        std::string(o.algorithm == "sbplx"    ? "SBPLX"
                    : o.algorithm == "bobyqa" ? "BOBYQA"
                                              : "NELDERMEAD") +
        ", " + std::to_string(t.evals) + " evaluations (budget " + std::to_string(o.maxeval) +
        ", NLopt result " + r.result + "). Training: " + std::to_string(t.train->size()) +
        " random maps " + std::to_string(o.size[0]) + "x" + std::to_string(o.size[1]) + "x" +
        std::to_string(o.size[2]) + " m, " + std::to_string(o.columns) +
        " columns (seeds 2000..); held out: " + o.heldout +
        ". Objective J = mean over maps of [flight time / flight time at the defaults + 0.05 x "
        "turns + 1 if infeasible] (10 for a failed map); lower is better. Why Subplex (SBPLX): "
        "J is deterministic but piecewise constant in the parameters (grid paths and turn counts "
        "change in jumps), so model-based methods such as BOBYQA see flat or meaningless local "
        "models; a derivative-free simplex method with large initial steps (0.25 of each range) "
        "moves across the plateaus, and Subplex is NLopt's more robust Nelder-Mead variant. "
        "Parameter bounds (tdo/params.h tune ranges): " +
        bounds + ".\n\n";
  std::string head = "| |";
  std::string rule = "|---|";
  std::string defaults = "| paper (defaults) |";
  std::string tuned = "| tuned |";
  for (std::size_t i = 0; i < t.params.size(); ++i) {
    const Tuned& p = t.params[i];
    head += " " + p.name + (p.unit.empty() ? "" : " (deg)") + " |";
    rule += "---:|";
    defaults += " " + fmt(p.def, "%g") + " |";
    tuned += " " + fmt(r.best[i], "%.4g") + " |";
  }
  md += head + " J training | J held-out |\n" + rule + "---:|---:|\n";
  md += defaults + " " + fmt(r.j_train_default, "%.4f") + " | " + fmt(r.j_held_default, "%.4f") +
        " |\n";
  md += tuned + " " + fmt(r.j_train_tuned, "%.4f") + " | " + fmt(r.j_held_tuned, "%.4f") + " |\n\n";
  md +=
      "Held-out maps, defaults -> tuned:\n\n| map | length (m) | turns | flight time (s) | "
      "feasible | plan time (ms) |\n|---|---:|---:|---:|---:|---:|\n";
  for (std::size_t i = 0; i < held.size(); ++i) {
    const MapEval& a = r.ref_held[i];
    const MapEval& b = r.tuned_held[i];
    md += "| " + held[i].name + " | " + fmt(a.length, "%.2f") + " -> " + fmt(b.length, "%.2f") +
          " | " + fmt(a.turns, "%.0f") + " -> " + fmt(b.turns, "%.0f") + " | " +
          fmt(a.flight_time, "%.2f") + " -> " + fmt(b.flight_time, "%.2f") + " | " +
          (a.feasible ? "yes" : "no") + " -> " + (b.feasible ? "yes" : "no") + " | " +
          fmt(a.plan_ms, "%.1f") + " -> " + fmt(b.plan_ms, "%.1f") + " |\n";
  }
  md += std::string("\nGeneralisation: the tuned parameters ") +
        (r.j_held_tuned < r.j_held_default - 1e-9    ? "also lower J on the held-out maps."
         : r.j_held_tuned <= r.j_held_default + 1e-9 ? "leave J on the held-out maps unchanged."
                                                     : "raise J on the held-out maps: they do "
                                                       "not generalise from the training maps.") +
        "\n";
  return md;
}

void write_outputs(const Options& o, const fs::path& dir, const Tuner& t, const Outcome& r,
                   const std::vector<tdo_bench::MapCase>& held) {
  write_file(dir / "tune_evaluations.csv", evaluations_csv(t));
  write_file(dir / "tune.md", tune_md(o, t, r, held));
  std::string c2 = "set,params,J\n";
  c2 += "train,default," + fmt(r.j_train_default, "%.6g") + "\ntrain,tuned," +
        fmt(r.j_train_tuned, "%.6g") + "\nheldout,default," + fmt(r.j_held_default, "%.6g") +
        "\nheldout,tuned," + fmt(r.j_held_tuned, "%.6g") + "\n";
  write_file(dir / "tune.csv", c2);
  std::printf("evaluations: %d\nJ train %.5f -> %.5f, held-out %.5f -> %.5f\n", t.evals,
              r.j_train_default, r.j_train_tuned, r.j_held_default, r.j_held_tuned);
  std::string line = "tuned";
  for (std::size_t i = 0; i < t.params.size(); ++i)
    line += " " + t.params[i].name + " " + fmt(r.best[i], "%.4g") + t.params[i].unit;
  std::printf("%s\n", line.c_str());
}

int run(int argc, char** argv) {
  Options o;
  const int parsed = parse_options(argc, argv, &o);
  if (parsed >= 0) return parsed;
  const fs::path dir(o.out);
  fs::create_directories(dir / "maps");
  std::vector<tdo_bench::MapCase> train;
  std::vector<tdo_bench::MapCase> held;
  load_cases(o, dir, &train, &held);

  Tuner t;
  std::string err;
  t.train = &train;
  t.tdo = tdo_baselines::make_planner("tdo", &err);
  t.ref_train = t.run(train, t.defaults());
  Outcome r;
  r.ref_held = t.run(held, t.defaults());
  r.best = optimise(o, &t, &r.result);
  // The optimiser's best point may be worse than the start only if it never improved: keep p0.
  r.j_train_default = Tuner::objective(t.ref_train, t.ref_train);
  r.j_train_tuned = Tuner::objective(t.run(train, r.best), t.ref_train);
  if (!(r.j_train_tuned <= r.j_train_default)) {
    r.best = t.defaults();
    r.j_train_tuned = r.j_train_default;
  }
  r.tuned_held = t.run(held, r.best);
  r.j_held_default = Tuner::objective(r.ref_held, r.ref_held);
  r.j_held_tuned = Tuner::objective(r.tuned_held, r.ref_held);
  write_outputs(o, dir, t, r, held);
  return 0;
}

}  // namespace

int main(int argc, char** argv) { return tdo_tool::guarded_main("tdo-tune", run, argc, argv); }
