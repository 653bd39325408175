// Messages <-> libtdo structs, with every check named (adapters.h).
#include "tdo_lcm/adapters.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "tdo/config.h"
#include "tdo/params.h"
#include "tdo/status.h"
#include "tdo_lcm/request_fields.h"
#include "tdo_lcm/rle.h"
#include "tdo_samples/samples.h"

namespace tdo_lcm {
namespace {

// The message constants are the library's enum values; keep them so.
static_assert(tdo::plan_request_t::DEPTH_SEARCH == TDO_PLAN_SEARCH, "depth");
static_assert(tdo::plan_request_t::DEPTH_CORRECT == TDO_PLAN_CORRECT, "depth");
static_assert(tdo::plan_request_t::DEPTH_SMOOTH == TDO_PLAN_SMOOTH, "depth");
static_assert(tdo::plan_request_t::DEPTH_TRAJECTORY == TDO_PLAN_TRAJECTORY, "depth");
static_assert(tdo::plan_request_t::SEARCH_ASTAR == TDO_SEARCH_ASTAR, "search");
static_assert(tdo::plan_request_t::SEARCH_BIDIR == TDO_SEARCH_BIDIR, "search");
static_assert(tdo::plan_request_t::CORRECT_MULTISCALE == TDO_CORRECT_MULTISCALE, "correction");
static_assert(tdo::plan_request_t::CORRECT_GREEDY_LOS == TDO_CORRECT_GREEDY_LOS, "correction");
static_assert(tdo::plan_request_t::CORRECT_NONE == TDO_CORRECT_NONE, "correction");
static_assert(tdo::plan_request_t::SMOOTHING_G2 == TDO_SMOOTHING_G2, "smoothing");
static_assert(tdo::plan_request_t::SMOOTHING_ARC == TDO_SMOOTHING_ARC, "smoothing");
static_assert(tdo::plan_request_t::SMOOTHING_NONE == TDO_SMOOTHING_NONE, "smoothing");
static_assert(tdo::plan_request_t::GRID_FIRST_OFF == TDO_GRID_FIRST_OFF, "grid_first");
static_assert(tdo::plan_request_t::GRID_FIRST_PLAIN == TDO_GRID_FIRST_PLAIN, "grid_first");
static_assert(tdo::plan_request_t::GRID_FIRST_TERMS == TDO_GRID_FIRST_TERMS, "grid_first");
static_assert(tdo::plan_request_t::STATES_HEADING == TDO_STATES_HEADING, "states");
static_assert(tdo::plan_request_t::STATES_VOXEL == TDO_STATES_VOXEL, "states");
static_assert(tdo::feasibility_t::QUANTITY_SPEED == TDO_QUANTITY_SPEED, "quantity");
static_assert(tdo::feasibility_t::QUANTITY_ACCELERATION == TDO_QUANTITY_ACCELERATION, "quantity");
static_assert(tdo::feasibility_t::QUANTITY_JERK == TDO_QUANTITY_JERK, "quantity");
static_assert(tdo::feasibility_t::QUANTITY_TURN_RADIUS == TDO_QUANTITY_TURN_RADIUS, "quantity");
static_assert(tdo::feasibility_t::QUANTITY_CLEARANCE == TDO_QUANTITY_CLEARANCE, "quantity");

constexpr uint64_t kMaxCount = static_cast<uint64_t>(std::numeric_limits<int32_t>::max());

std::string idx(const char* name, std::size_t i) {
  return std::string(name) + "[" + std::to_string(i) + "]";
}

Check need_finite(const char* name, double v) {
  if (std::isfinite(v)) return {};
  return fail_field(Reason::non_finite, name, std::string(name) + " = " + exact_num(v));
}

Check need_finite3(const char* name, const double* v) {
  for (std::size_t i = 0; i < 3; ++i)
    if (!std::isfinite(v[i]))
      return fail_field(Reason::non_finite, idx(name, i), idx(name, i) + " = " + exact_num(v[i]));
  return {};
}

/** Metric that may be +inf (HUGE_VAL) but never NaN. */
Check need_not_nan(const char* name, double v) {
  if (!std::isnan(v)) return {};
  return fail(Reason::non_finite, std::string(name) + " is NaN");
}

Check need_count(const char* name, int32_t n, std::size_t size) {
  if (n >= 0 && static_cast<std::size_t>(n) == size) return {};
  return fail(Reason::count_mismatch, std::string(name) + ": count " + std::to_string(n) +
                                          ", array of " + std::to_string(size));
}

Check need_rows(const char* name, int32_t n, const std::vector<std::vector<double>>& rows,
                std::size_t width) {
  Check c = need_count(name, n, rows.size());
  if (!c.ok()) return c;
  for (std::size_t i = 0; i < rows.size(); ++i)
    if (rows[i].size() != width)
      return fail(Reason::count_mismatch, idx(name, i) + " has " + std::to_string(rows[i].size()) +
                                              " numbers, not " + std::to_string(width));
  return {};
}

/**
 * Cells of the library's clearance stencil (grid.cpp build_stencil), counting stops past `cap`.
 * Like the library it answers in constant time when the cube of offsets that is surely inside
 * ((2m + 1)^3 cells, sqrt(3) (m - 1/2) res < clearance) already exceeds `cap`.
 */
uint64_t stencil_cells(double clearance, double res, uint64_t cap) {
  const double q = clearance / res;
  if (!(q < 1.0e9)) return cap + 1u;
  const double m = std::floor(q / std::sqrt(3.0) + 0.5) - 1.0;
  if (m >= 1.0 && (2.0 * m + 1.0) * (2.0 * m + 1.0) * (2.0 * m + 1.0) > static_cast<double>(cap))
    return cap + 1u;
  const double ratio = q + 0.5;
  const int32_t reach = static_cast<int32_t>(std::ceil(ratio));
  const double c2 = clearance * clearance;
  uint64_t n = 0;
  for (int32_t dk = -reach; dk <= reach; ++dk) {
    for (int32_t dj = -reach; dj <= reach; ++dj) {
      for (int32_t di = -reach; di <= reach; ++di) {
        const double gx = std::fmax(0.0, std::fabs(static_cast<double>(di)) * res - 0.5 * res);
        const double gy = std::fmax(0.0, std::fabs(static_cast<double>(dj)) * res - 0.5 * res);
        const double gz = std::fmax(0.0, std::fabs(static_cast<double>(dk)) * res - 0.5 * res);
        if (!(gx * gx + gy * gy + gz * gz < c2)) continue;
        if (++n > cap) return n;
      }
    }
  }
  return n;
}

Check check_box(std::size_t i, const double* b) {
  for (std::size_t a = 0; a < 6; ++a)
    if (!std::isfinite(b[a]))
      return fail(Reason::non_finite, "boxes[" + std::to_string(i) + "][" + std::to_string(a) +
                                          "] = " + exact_num(b[a]));
  static const char* const kAxis[3] = {"x", "y", "z"};
  for (std::size_t a = 0; a < 3; ++a)
    if (!(b[a + 3] > b[a]))
      return fail(Reason::out_of_range,
                  idx("boxes", i) + ": max <= min on the " + kAxis[a] + " axis");
  return {};
}

Check check_desc(const tdo_grid_desc& d) {
  if (d.nx <= 0 || d.ny <= 0 || d.nz <= 0)
    return fail(Reason::out_of_range, "size " + std::to_string(d.nx) + " x " +
                                          std::to_string(d.ny) + " x " + std::to_string(d.nz) +
                                          ": each must be > 0");
  Check c = need_finite("resolution", d.res);
  if (!c.ok()) return c;
  if (!(d.res > 0.0)) return fail(Reason::out_of_range, "resolution " + exact_num(d.res) + " <= 0");
  const double o[3] = {d.origin.x, d.origin.y, d.origin.z};
  return need_finite3("origin", o);
}

tdo_grid_desc desc_of(const tdo::map_t& m) {
  tdo_grid_desc d{};
  d.nx = m.size[0];
  d.ny = m.size[1];
  d.nz = m.size[2];
  d.res = m.resolution;
  d.origin = tdo_vec3{m.origin[0], m.origin[1], m.origin[2]};
  return d;
}

Check count_of(const char* name, uint64_t n, int32_t* out) {
  if (n > kMaxCount)
    return fail(Reason::too_large, std::string(name) + ": " + std::to_string(n) + " > INT32_MAX");
  *out = static_cast<int32_t>(n);
  return {};
}

Check copy_points(const char* name, const tdo_vec3* p, uint32_t n, int32_t* count,
                  std::vector<std::vector<double>>* out) {
  Check c = count_of(name, n, count);
  if (!c.ok()) return c;
  if (n > 0 && p == nullptr)
    return fail(Reason::count_mismatch, std::string(name) + ": no array for " + std::to_string(n));
  out->assign(n, std::vector<double>(3, 0.0));
  for (uint32_t i = 0; i < n; ++i) {
    const double v[3] = {p[i].x, p[i].y, p[i].z};
    c = need_finite3(idx(name, i).c_str(), v);
    if (!c.ok()) return c;
    (*out)[i] = {v[0], v[1], v[2]};
  }
  return {};
}

}  // namespace

// ---- maps ------------------------------------------------------------------------------------

Check clearance_check(double clearance, double res, const tdo_capacity& cap) {
  Check c = need_finite("clearance", clearance);
  if (c.ok()) c = need_finite("resolution", res);
  if (!c.ok()) return c;
  if (clearance < 0.0)
    return fail(Reason::out_of_range, "clearance " + exact_num(clearance) + " < 0");
  if (!(res > 0.0)) return fail(Reason::out_of_range, "resolution " + exact_num(res) + " <= 0");
  if (stencil_cells(clearance, res, cap.max_clear_cells) > cap.max_clear_cells)
    return fail(Reason::map_capacity, "clearance " + exact_num(clearance) + " m at resolution " +
                                          exact_num(res) + " m needs more than " +
                                          std::to_string(cap.max_clear_cells) + " stencil cells");
  return {};
}

double effective_clearance(const tdo::map_t& m, double requested) {
  return requested < 0.0 ? m.clearance : requested;  // NaN stays NaN and fails the checks
}

// "; it needs an arena of B bytes": the footprint of these capacities with room for n voxels
// (the node pools and the other capacities stay as configured, so it is a lower bound when they
// were sized from the voxels too).
static std::string arena_needed(const tdo_capacity& cap, uint64_t n) {
  if (n > 0xFFFFFFF0u) return "; more than 2^32 voxels: no planner arena can hold it";
  tdo_planner_config cfg{};
  cfg.cap = cap;
  cfg.cap.max_voxels = static_cast<uint32_t>(n);
  cfg.cap.max_axis = 0;
  const std::size_t bytes = tdo_planner_footprint(&cfg);
  return bytes == 0 ? std::string()
                    : "; it needs an arena of at least " + std::to_string(bytes) + " bytes";
}

Check map_check(const tdo::map_t& m, const tdo_capacity& cap, double clearance) {
  Check c = check_counts(m);
  if (!c.ok()) return c;
  if (m.map_id < 0)
    return fail(Reason::out_of_range, "map_id " + std::to_string(m.map_id) + " < 0");
  const tdo_grid_desc d = desc_of(m);
  c = check_desc(d);
  if (!c.ok()) return c;
  c = need_finite("clearance", m.clearance);
  if (!c.ok()) return c;
  if (m.clearance < 0.0)
    return fail(Reason::out_of_range, "clearance " + exact_num(m.clearance) + " < 0");
  const double clear = effective_clearance(m, clearance);
  c = need_finite("requested clearance", clear);
  if (!c.ok()) return c;

  const uint64_t n =
      static_cast<uint64_t>(d.nx) * static_cast<uint64_t>(d.ny) * static_cast<uint64_t>(d.nz);
  if (n > cap.max_voxels)
    return fail(Reason::map_capacity, std::to_string(d.nx) + " x " + std::to_string(d.ny) + " x " +
                                          std::to_string(d.nz) + " = " + std::to_string(n) +
                                          " voxels, more than the capacity of " +
                                          std::to_string(cap.max_voxels) + arena_needed(cap, n));
  if (m.boxes.size() > cap.max_boxes)
    return fail(Reason::map_capacity, std::to_string(m.boxes.size()) +
                                          " boxes, more than the capacity of " +
                                          std::to_string(cap.max_boxes));
  for (std::size_t i = 0; i < m.boxes.size(); ++i) {
    c = check_box(i, m.boxes[i].data());
    if (!c.ok()) return c;
  }
  c = clearance_check(clear, d.res, cap);
  if (!c.ok()) return c;

  switch (m.encoding) {
    case tdo::map_t::ENCODING_RLE:
      if (!m.data.empty())
        return fail(Reason::out_of_range, "ENCODING_RLE with " + std::to_string(m.data.size()) +
                                              " bytes of data (must be empty)");
      return rle_check(m.runs, n, nullptr);
    case tdo::map_t::ENCODING_OCTOMAP_BT:
      return fail(Reason::unsupported_encoding, "ENCODING_OCTOMAP_BT is not decoded by this build");
    default:
      return fail(Reason::bad_encoding, "encoding " + std::to_string(m.encoding));
  }
}

Check map_to_grid(const tdo::map_t& m, const tdo_capacity& cap, double clearance, tdo_grid* grid) {
  if (grid == nullptr) return fail(Reason::grid_error, "no grid");
  Check c = map_check(m, cap, clearance);
  if (!c.ok()) return c;
  const tdo_grid_desc d = desc_of(m);
  tdo_status st = tdo_grid_reset(grid, &d);
  if (st != TDO_OK)
    return fail(Reason::grid_error, std::string("tdo_grid_reset: ") + tdo_status_str(st));
  for (const std::vector<double>& b : m.boxes) {
    const tdo_box box{{b[0], b[1], b[2]}, {b[3], b[4], b[5]}};
    st = tdo_grid_add_box(grid, &box);
    if (st != TDO_OK)
      return fail(Reason::grid_error, std::string("tdo_grid_add_box: ") + tdo_status_str(st));
  }
  const uint64_t nx = static_cast<uint64_t>(d.nx);
  const uint64_t nxy = nx * static_cast<uint64_t>(d.ny);
  rle_for_each_occupied(m.runs, [&](uint64_t i) {
    st = tdo_grid_add_voxel(grid, static_cast<int32_t>(i % nx),
                            static_cast<int32_t>((i % nxy) / nx), static_cast<int32_t>(i / nxy));
    return st == TDO_OK;
  });
  if (st != TDO_OK)
    return fail(Reason::grid_error, std::string("tdo_grid_add_voxel: ") + tdo_status_str(st));
  st = tdo_grid_finish(grid, effective_clearance(m, clearance));
  if (st != TDO_OK)
    return fail(Reason::grid_error, std::string("tdo_grid_finish: ") + tdo_status_str(st));
  return {};
}

Check map_from_occupancy(const tdo_grid_desc& desc, const std::vector<uint8_t>& occupancy,
                         const std::vector<tdo_box>& boxes, double clearance, tdo::map_t* out) {
  Check c = check_desc(desc);
  if (!c.ok()) return c;
  c = need_finite("clearance", clearance);
  if (!c.ok()) return c;
  if (clearance < 0.0)
    return fail(Reason::out_of_range, "clearance " + exact_num(clearance) + " < 0");
  const uint64_t n = static_cast<uint64_t>(desc.nx) * static_cast<uint64_t>(desc.ny) *
                     static_cast<uint64_t>(desc.nz);
  if (!occupancy.empty() && occupancy.size() != n)
    return fail(Reason::count_mismatch, "occupancy of " + std::to_string(occupancy.size()) +
                                            " voxels, the grid has " + std::to_string(n));
  std::vector<std::vector<double>> rows;
  rows.reserve(boxes.size());
  for (std::size_t i = 0; i < boxes.size(); ++i) {
    const tdo_box& b = boxes[i];
    rows.push_back({b.min.x, b.min.y, b.min.z, b.max.x, b.max.y, b.max.z});
    c = check_box(i, rows.back().data());
    if (!c.ok()) return c;
  }
  std::vector<int32_t> runs = occupancy.empty() ? std::vector<int32_t>{} : rle_encode(occupancy);
  int32_t n_runs = 0;
  int32_t n_boxes = 0;
  c = count_of("runs", runs.size(), &n_runs);
  if (c.ok()) c = count_of("boxes", rows.size(), &n_boxes);
  if (!c.ok()) return c;

  *out = tdo::map_t{};
  out->map_id = 0;
  out->vehicle_id = -1;
  out->resolution = desc.res;
  out->origin[0] = desc.origin.x;
  out->origin[1] = desc.origin.y;
  out->origin[2] = desc.origin.z;
  out->size[0] = desc.nx;
  out->size[1] = desc.ny;
  out->size[2] = desc.nz;
  out->clearance = clearance;
  out->encoding = tdo::map_t::ENCODING_RLE;
  out->n_runs = n_runs;
  out->runs = std::move(runs);
  out->n_bytes = 0;
  out->n_boxes = n_boxes;
  out->boxes = std::move(rows);
  return {};
}

std::vector<uint8_t> grid_occupancy(const tdo_grid* grid) {
  std::vector<uint8_t> occ;
  if (grid == nullptr) return occ;
  const tdo_grid_desc d = tdo_grid_get_desc(grid);
  if (d.nx <= 0 || d.ny <= 0 || d.nz <= 0) return occ;
  occ.reserve(static_cast<std::size_t>(d.nx) * static_cast<std::size_t>(d.ny) *
              static_cast<std::size_t>(d.nz));
  for (int32_t k = 0; k < d.nz; ++k)
    for (int32_t j = 0; j < d.ny; ++j)
      for (int32_t i = 0; i < d.nx; ++i)
        occ.push_back(tdo_grid_is_occupied(grid, tdo_voxel{i, j, k}) ? 1u : 0u);
  return occ;
}

// ---- plan requests ---------------------------------------------------------------------------

namespace {

const tdo_param_info* row_of(const RequestField& f) {
  return f.param >= 0 ? tdo_param_at(static_cast<uint32_t>(f.param)) : nullptr;
}

/** `m` with libtdo's default in every field whose use_defaults bit is set (tdo/params.h: a row
 *  with default_of takes the request's value of that row, once resolved: a_lat_max <- a_max). */
tdo::plan_request_t with_defaults(const tdo::plan_request_t& in) {
  tdo::plan_request_t m = in;
  if (in.use_defaults == 0) return m;
  tdo_plan_params d{};
  tdo_plan_params_default(&d);
  for (const RequestField& f : request_fields()) {  // a default_of source comes first
    if ((in.use_defaults & f.use_default_bit) == 0) continue;
    const tdo_param_info* row = row_of(f);
    if (row == nullptr) {
      f.set(m, f.own_default);
      continue;
    }
    double v = tdo_param_get(&d, static_cast<uint32_t>(f.param));
    if (row->default_of >= 0) {
      for (const RequestField& src : request_fields())
        if (src.param == row->default_of) v = src.get(m);
    }
    f.set(m, v);
  }
  return m;
}

std::string range_text(const tdo_param_info& r) {
  if (std::isinf(r.max)) return std::string(r.min_open ? "> " : ">= ") + exact_num(r.min);
  return std::string(r.min_open ? "(" : "[") + exact_num(r.min) + ", " + exact_num(r.max) +
         (r.max_open ? ")" : "]");
}

/** Finite numbers; integer fields inside their row's values (ENUM, BOOL: bad_enum; UINT:
 *  out_of_range), whatever the depth. */
Check field_types(const tdo::plan_request_t& m) {
  for (const RequestField& f : request_fields()) {
    if (f.integer) continue;
    const Check c = need_finite(f.name, f.get(m));
    if (!c.ok()) return c;
  }
  for (const RequestField& f : request_fields()) {
    const tdo_param_info* row = row_of(f);
    if (!f.integer || row == nullptr) continue;
    const double v = f.get(m);
    if (tdo_param_valid(static_cast<uint32_t>(f.param), v) != 0) continue;
    if (row->type == TDO_PARAM_UINT)
      return fail_field(Reason::out_of_range, f.name,
                        std::string(f.name) + " " + exact_num(v) + " < " + exact_num(row->min));
    return fail_field(Reason::bad_enum, f.name, std::string(f.name) + " " + exact_num(v));
  }
  return {};
}

/** The library's ranges (tdo/params.h) of the stages the request's depth runs, checked here so
 *  that a refusal names the field. */
Check library_ranges(const tdo::plan_request_t& m) {
  for (const RequestField& f : request_fields()) {
    const tdo_param_info* row = row_of(f);
    if (row == nullptr || f.integer || m.depth < row->stage) continue;
    const double v = f.get(m);
    if (tdo_param_valid(static_cast<uint32_t>(f.param), v) == 0)
      return fail_field(
          Reason::out_of_range, f.name,
          std::string(f.name) + " = " + exact_num(v) + ": must be " + range_text(*row));
  }
  return {};
}

/** The moving start (start_vel, start_acc): finite, within v_max and a_max, only with the
 *  trajectory stage (tdo_planner_plan's rules, named by field here). */
Check start_state_check(const tdo::plan_request_t& m) {
  Check c = need_finite3("start_vel", m.start_vel);
  if (c.ok()) c = need_finite3("start_acc", m.start_acc);
  if (!c.ok()) return c;
  const double speed = std::sqrt(m.start_vel[0] * m.start_vel[0] + m.start_vel[1] * m.start_vel[1] +
                                 m.start_vel[2] * m.start_vel[2]);
  const double acc = std::sqrt(m.start_acc[0] * m.start_acc[0] + m.start_acc[1] * m.start_acc[1] +
                               m.start_acc[2] * m.start_acc[2]);
  if (!(speed > 0.0) && !(acc > 0.0)) return {};
  if (m.depth != tdo::plan_request_t::DEPTH_TRAJECTORY)
    return fail_field(Reason::out_of_range, "start_vel",
                      "a moving start needs depth " +
                          std::to_string(tdo::plan_request_t::DEPTH_TRAJECTORY) + ", not " +
                          std::to_string(m.depth));
  if (speed > m.v_max * (1.0 + 1e-9))  // the library's rounding allowance (trajectory.h)
    return fail_field(Reason::out_of_range, "start_vel",
                      "start speed " + exact_num(speed) + " m/s above v_max " + exact_num(m.v_max));
  if (acc > m.a_max * (1.0 + 1e-9))
    return fail_field(
        Reason::out_of_range, "start_acc",
        "start acceleration " + exact_num(acc) + " m/s^2 above a_max " + exact_num(m.a_max));
  return {};
}

}  // namespace

Check plan_request_from_msg(const tdo::plan_request_t& msg, int32_t vehicle_id,
                            tdo_plan_request* out, double* clearance) {
  if (msg.use_defaults < 0 || msg.use_defaults > tdo::plan_request_t::USE_DEFAULT_ALL)
    return fail_field(
        Reason::out_of_range, "use_defaults",
        "use_defaults " + std::to_string(msg.use_defaults) + ": bits outside USE_DEFAULT_ALL");
  const tdo::plan_request_t m = with_defaults(msg);
  if (m.vehicle_id != vehicle_id)
    return fail(Reason::other_vehicle, "request for vehicle " + std::to_string(m.vehicle_id) +
                                           ", this planner serves vehicle " +
                                           std::to_string(vehicle_id));
  if (m.map_id < -1)
    return fail_field(Reason::out_of_range, "map_id",
                      "map_id " + std::to_string(m.map_id) + " < -1");
  Check c = need_finite3("start", m.start);
  if (c.ok()) c = need_finite3("goal", m.goal);
  if (c.ok()) c = field_types(m);
  if (!c.ok()) return c;
  if (m.samples != tdo::plan_request_t::SAMPLES_OFF && m.samples != tdo::plan_request_t::SAMPLES_ON)
    return fail_field(Reason::bad_enum, "samples", "samples " + std::to_string(m.samples));
  c = library_ranges(m);
  if (c.ok()) c = start_state_check(m);
  if (!c.ok()) return c;

  tdo_plan_request r{};
  r.start = tdo_vec3{m.start[0], m.start[1], m.start[2]};
  r.goal = tdo_vec3{m.goal[0], m.goal[1], m.goal[2]};
  tdo_plan_params_default(&r.params);
  for (const RequestField& f : request_fields()) {
    // Every value is one the field can hold (field_types); a value outside its range at a depth
    // that does not run its stage is carried as it is, as the library ignores it.
    if (f.param >= 0 &&
        tdo_param_set(&r.params, static_cast<uint32_t>(f.param), f.get(m)) != TDO_OK)
      return fail_field(Reason::out_of_range, f.name, std::string(f.name) + " cannot be held");
  }
  r.state.v = tdo_vec3{m.start_vel[0], m.start_vel[1], m.start_vel[2]};
  r.state.a = tdo_vec3{m.start_acc[0], m.start_acc[1], m.start_acc[2]};
  *out = r;
  if (clearance != nullptr) *clearance = m.clearance;
  return {};
}

void plan_request_to_msg(const tdo_plan_request& req, double clearance, tdo::plan_request_t* out) {
  out->start[0] = req.start.x;
  out->start[1] = req.start.y;
  out->start[2] = req.start.z;
  out->goal[0] = req.goal.x;
  out->goal[1] = req.goal.y;
  out->goal[2] = req.goal.z;
  out->start_vel[0] = req.state.v.x;
  out->start_vel[1] = req.state.v.y;
  out->start_vel[2] = req.state.v.z;
  out->start_acc[0] = req.state.a.x;
  out->start_acc[1] = req.state.a.y;
  out->start_acc[2] = req.state.a.z;
  out->clearance = clearance;
  for (const RequestField& f : request_fields()) {
    if (f.param < 0) continue;
    double v = tdo_param_get(&req.params, static_cast<uint32_t>(f.param));
    if (f.integer) v = std::min(f.hi, std::max(f.lo, v));  // max_expansions above INT32_MAX
    f.set(*out, v);
  }
}

// ---- answers ---------------------------------------------------------------------------------

namespace {

// What every answer (trajectory, feasibility report) carries: the request's ids and the status.
template <typename Msg>
void put_answer_head(const AnswerIds& ids, tdo_status status, Msg* m) {
  m->utime = ids.utime;
  m->request_id = ids.request_id;
  m->request_seq = ids.request_seq;
  m->vehicle_id = ids.vehicle_id;
  m->status_code = static_cast<int32_t>(status);
  m->status = tdo_status_str(status);
}

}  // namespace

Check trajectory_to_msg(const tdo_plan_result& r, const tdo_plan_request& req, const AnswerIds& ids,
                        double plan_ms, tdo::trajectory_t* out, bool with_samples,
                        const tdo_planner* planner) {
  tdo::trajectory_t t{};
  put_answer_head(ids, r.status, &t);
  t.map_id = ids.map_id;
  t.reached = r.n_grid_path > 0 ? static_cast<int8_t>(r.reached) : int8_t{-1};
  Check c = copy_points("grid_path", r.grid_path, r.n_grid_path, &t.n_grid_path, &t.grid_path);
  if (c.ok())
    c = copy_points("waypoints", r.waypoints, r.n_waypoints, &t.n_waypoints, &t.waypoints);
  if (c.ok() && with_samples) c = count_of("samples", r.n_samples, &t.n_samples);
  if (!c.ok()) return c;
  if (with_samples && r.n_samples > 0 && r.samples == nullptr && planner == nullptr)
    return fail(Reason::count_mismatch, "samples: no array for " + std::to_string(r.n_samples));
  // Stored or regenerated by the planner (tdo_capacity.stream_samples): the same samples.
  std::vector<tdo_sample> samples;
  if (with_samples) {
    const tdo_status st = tdo_samples::plan_samples(planner, r, &samples);
    if (st != TDO_OK)
      return fail(Reason::library_error,
                  std::string("tdo_planner_each_sample: ") + tdo_status_str(st));
  }
  t.dt = req.params.dt;
  const auto n_samples = static_cast<uint32_t>(samples.size());
  t.samples.assign(n_samples, std::vector<double>(10, 0.0));
  for (uint32_t i = 0; i < n_samples; ++i) {
    const tdo_sample& s = samples[i];
    const std::vector<double> row = {s.t,   s.p.x, s.p.y, s.p.z, s.v.x,
                                     s.v.y, s.v.z, s.a.x, s.a.y, s.a.z};
    for (std::size_t a = 0; a < row.size(); ++a)
      if (!std::isfinite(row[a]))
        return fail(Reason::non_finite, "samples[" + std::to_string(i) + "][" + std::to_string(a) +
                                            "] = " + exact_num(row[a]));
    t.samples[i] = row;
  }
  const tdo_metrics& m = r.metrics;
  for (uint32_t i = 0; i < tdo_metric_count(); ++i) {
    c = need_not_nan(tdo_metric_name(i), tdo_metric_value(&m, i));
    if (!c.ok()) return c;
  }
  c = need_not_nan("plan_time_ms", plan_ms);
  if (c.ok()) c = need_not_nan("search_cost", r.search.cost);
  if (c.ok()) c = count_of("turns", m.turns, &t.turns);
  if (c.ok()) c = count_of("expansions", r.search.expansions, &t.expansions);
  if (!c.ok()) return c;
  t.length_m = m.length_m;
  t.total_turn_deg = m.total_turn_deg;
  t.min_clearance_m = m.min_clearance_m;
  t.avg_curvature = m.avg_curvature;
  t.smoothness = m.smoothness;
  t.energy = m.energy;
  t.flight_time_s = m.flight_time_s;
  t.plan_time_ms = plan_ms;
  t.search_cost = r.search.cost;
  *out = std::move(t);
  return {};
}

Check feasibility_to_msg(const tdo_plan_result& r, const tdo_plan_request& req, double clearance,
                         const AnswerIds& ids, tdo::feasibility_t* out) {
  tdo::feasibility_t f{};
  put_answer_head(ids, r.status, &f);
  f.checked = r.reached == TDO_PLAN_TRAJECTORY && r.n_grid_path > 0;
  const tdo_feasibility& q = r.feasibility;
  f.ok = f.checked && q.ok != 0;
  const struct {
    const char* name;
    double value;
  } values[] = {{"max_speed", q.max_speed},
                {"max_acc", q.max_acc},
                {"max_jerk", q.max_jerk},
                {"min_turn_radius", q.min_turn_radius},
                {"min_clearance", q.min_clearance}};
  Check c;
  for (const auto& v : values) {
    c = need_not_nan(v.name, v.value);
    if (!c.ok()) return c;
  }
  f.max_speed = q.max_speed;
  f.max_acc = q.max_acc;
  f.max_jerk = q.max_jerk;
  f.min_turn_radius = q.min_turn_radius;
  f.min_clearance = q.min_clearance;
  c = count_of("refinements", r.refinements, &f.refinements);
  if (c.ok()) c = count_of("n_violations_total", q.n_violations_total, &f.n_violations_total);
  if (c.ok()) c = count_of("violations", q.n_violations, &f.n_violations);
  if (!c.ok()) return c;
  f.v_max = req.params.v_max;
  f.a_max = req.params.a_max;
  f.j_max = req.params.j_max;
  f.clearance = clearance;
  if (q.n_violations > 0 && q.violations == nullptr)
    return fail(Reason::count_mismatch,
                "violations: no array for " + std::to_string(q.n_violations));
  for (uint32_t i = 0; i < q.n_violations; ++i) {
    const tdo_violation& v = q.violations[i];
    c = need_not_nan(idx("violation_value", i).c_str(), v.value);
    if (c.ok()) c = need_not_nan(idx("violation_limit", i).c_str(), v.limit);
    if (c.ok()) c = need_not_nan(idx("violation_t", i).c_str(), v.t);
    if (!c.ok()) return c;
    f.violation_t.push_back(v.t);
    f.violation_what.push_back(static_cast<int8_t>(v.what));
    f.violation_value.push_back(v.value);
    f.violation_limit.push_back(v.limit);
  }
  *out = std::move(f);
  return {};
}

void error_answer(const AnswerIds& ids, int32_t status_code, const std::string& status,
                  const std::string& detail, tdo::trajectory_t* traj, tdo::feasibility_t* feas) {
  if (traj != nullptr) {
    *traj = tdo::trajectory_t{};
    traj->utime = ids.utime;
    traj->request_id = ids.request_id;
    traj->request_seq = ids.request_seq;
    traj->vehicle_id = ids.vehicle_id;
    traj->map_id = ids.map_id;
    traj->status_code = status_code;
    traj->status = status;
    traj->detail = detail;
    traj->reached = -1;
  }
  if (feas != nullptr) {
    *feas = tdo::feasibility_t{};
    feas->utime = ids.utime;
    feas->request_id = ids.request_id;
    feas->request_seq = ids.request_seq;
    feas->vehicle_id = ids.vehicle_id;
    feas->status_code = status_code;
    feas->status = status;
  }
}

Check samples_from_msg(const tdo::trajectory_t& m, std::vector<tdo_sample>* out) {
  Check c = need_rows("samples", m.n_samples, m.samples, 10);
  if (!c.ok()) return c;
  std::vector<tdo_sample> s(m.samples.size());
  for (std::size_t i = 0; i < m.samples.size(); ++i) {
    const std::vector<double>& row = m.samples[i];
    for (std::size_t a = 0; a < 10; ++a)
      if (!std::isfinite(row[a]))
        return fail(Reason::non_finite, "samples[" + std::to_string(i) + "][" + std::to_string(a) +
                                            "] = " + exact_num(row[a]));
    if (i > 0 && !(row[0] > m.samples[i - 1][0]))
      return fail(Reason::out_of_range, "samples[" + std::to_string(i) + "]: time " +
                                            exact_num(row[0]) + " not after " +
                                            exact_num(m.samples[i - 1][0]));
    s[i].t = row[0];
    s[i].p = tdo_vec3{row[1], row[2], row[3]};
    s[i].v = tdo_vec3{row[4], row[5], row[6]};
    s[i].a = tdo_vec3{row[7], row[8], row[9]};
  }
  *out = std::move(s);
  return {};
}

// ---- counts ----------------------------------------------------------------------------------

Check check_counts(const tdo::map_t& m) {
  Check c = need_count("runs", m.n_runs, m.runs.size());
  if (c.ok()) c = need_count("data", m.n_bytes, m.data.size());
  if (c.ok()) c = need_rows("boxes", m.n_boxes, m.boxes, 6);
  return c;
}

Check check_counts(const tdo::obstacles_t& m) {
  Check c = need_count("id", m.n, m.id.size());
  if (c.ok()) c = need_rows("position", m.n, m.position, 3);
  if (c.ok()) c = need_rows("velocity", m.n, m.velocity, 3);
  if (c.ok()) c = need_count("radius", m.n, m.radius.size());
  return c;
}

Check check_counts(const tdo::trajectory_t& m) {
  Check c = need_rows("grid_path", m.n_grid_path, m.grid_path, 3);
  if (c.ok()) c = need_rows("waypoints", m.n_waypoints, m.waypoints, 3);
  if (c.ok()) c = need_rows("samples", m.n_samples, m.samples, 10);
  // The compact form (compact.h): every array against its count.
  if (c.ok()) c = need_count("segment_kind", m.n_segments, m.segment_kind.size());
  if (c.ok()) c = need_count("segment_s0", m.n_segments, m.segment_s0.size());
  if (c.ok()) c = need_count("segment_length", m.n_segments, m.segment_length.size());
  if (c.ok()) c = need_count("segment_points", m.n_segment_points, m.segment_points.size());
  for (const auto* v :
       {&m.piece_t0, &m.piece_dur, &m.piece_s0, &m.piece_v0, &m.piece_a0, &m.piece_j})
    if (c.ok()) c = need_count("piece_*", m.n_pieces, v->size());
  return c;
}

Check check_counts(const tdo::feasibility_t& m) {
  Check c = need_count("violation_t", m.n_violations, m.violation_t.size());
  if (c.ok()) c = need_count("violation_what", m.n_violations, m.violation_what.size());
  if (c.ok()) c = need_count("violation_value", m.n_violations, m.violation_value.size());
  if (c.ok()) c = need_count("violation_limit", m.n_violations, m.violation_limit.size());
  return c;
}

Check check_counts(const tdo::status_t& m) {
  Check c = need_count("reason", m.n_reasons, m.reason.size());
  if (c.ok()) c = need_count("reason_count", m.n_reasons, m.reason_count.size());
  return c;
}

}  // namespace tdo_lcm
