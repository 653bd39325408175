/*
 * The embedded demo (tdo_demo.h): one source for the host program and the firmware.
 *
 * Output format, one record per line, numbers in fixed decimals (9 for metres and seconds), so a
 * byte-wise diff of two runs compares the plans digit by digit; fnv1a64 checksums cover the exact
 * bit patterns of the grid path, the path segments and the trajectory samples on top of that.
 */
#include "tdo_demo.h"

#include <math.h>
#include <string.h>

#include "tdo/tdo.h"
#include "tdo_demo_config.h"
#include "tdo_demo_map.h"

/* The planner's only memory: a static arena, so the image's RAM use is known at link time. */
unsigned char tdo_demo_arena[TDO_DEMO_ARENA_BYTES] __attribute__((aligned(16)));

/* ---- Text output without printf ---------------------------------------------------------- */

typedef struct line_buf {
  char text[160];
  size_t n;
} line_buf;

static void put_str(line_buf* l, const char* s) {
  while (*s != '\0' && l->n + 2u < sizeof(l->text)) l->text[l->n++] = *s++;
}

static void put_u64(line_buf* l, uint64_t v) {
  char digits[24];
  size_t n = 0;
  do {
    digits[n++] = (char)('0' + (int)(v % 10u));
    v /= 10u;
  } while (v != 0u && n < sizeof(digits));
  while (n > 0u && l->n + 2u < sizeof(l->text)) l->text[l->n++] = digits[--n];
}

static void put_u32(line_buf* l, uint32_t v) { put_u64(l, v); }

static void put_hex64(line_buf* l, uint64_t v) {
  static const char hex[] = "0123456789abcdef";
  put_str(l, "0x");
  for (int shift = 60; shift >= 0; shift -= 4) {
    char c[2] = {hex[(v >> shift) & 0xFu], '\0'};
    put_str(l, c);
  }
}

/* Fixed-point text of x with `dec` decimals (dec <= 9): round(|x| * 10^dec) half away from zero,
 * in integer digits. Pure IEEE double arithmetic, so equal doubles give equal text everywhere. */
static void put_fixed(line_buf* l, double x, unsigned dec) {
  if (isnan(x)) {
    put_str(l, "nan");
    return;
  }
  if (x < 0.0) put_str(l, "-");
  const double ax = fabs(x);
  if (isinf(ax)) {
    put_str(l, "inf");
    return;
  }
  uint64_t scale = 1u;
  for (unsigned i = 0; i < dec; ++i) scale *= 10u;
  const double scaled = floor(ax * (double)scale + 0.5);
  if (scaled >= 9.0e18) { /* beyond uint64: print the bit pattern instead */
    uint64_t bits;
    memcpy(&bits, &x, sizeof(bits));
    put_str(l, "bits:");
    put_hex64(l, bits);
    return;
  }
  const uint64_t u = (uint64_t)scaled;
  put_u64(l, u / scale);
  if (dec > 0u) {
    put_str(l, ".");
    uint64_t frac = u % scale;
    for (uint64_t d = scale / 10u; d > 0u; d /= 10u) {
      char c[2] = {(char)('0' + (int)(frac / d)), '\0'};
      put_str(l, c);
      frac %= d;
    }
  }
}

static void put_vec(line_buf* l, tdo_vec3 v) {
  put_fixed(l, v.x, 9);
  put_str(l, " ");
  put_fixed(l, v.y, 9);
  put_str(l, " ");
  put_fixed(l, v.z, 9);
}

static void emit(line_buf* l) {
  l->text[l->n++] = '\n';
  l->text[l->n] = '\0';
  tdo_demo_write(l->text);
  l->n = 0;
}

/* "key value" with a fixed-point value */
static void emit_fixed(const char* key, double v, unsigned dec) {
  line_buf l = {{0}, 0};
  put_str(&l, key);
  put_str(&l, " ");
  put_fixed(&l, v, dec);
  emit(&l);
}

static void emit_u32(const char* key, uint32_t v) {
  line_buf l = {{0}, 0};
  put_str(&l, key);
  put_str(&l, " ");
  put_u32(&l, v);
  emit(&l);
}

void tdo_demo_print_platform(const char* key, uint32_t value) {
  line_buf l = {{0}, 0};
  put_str(&l, "@");
  put_str(&l, key);
  put_str(&l, " ");
  put_u32(&l, value);
  emit(&l);
}

/* ---- Checksums of exact bit patterns ------------------------------------------------------ */

typedef struct fnv {
  uint64_t h;
} fnv;

static void fnv_bytes(fnv* f, const void* data, size_t n) {
  const unsigned char* p = (const unsigned char*)data;
  for (size_t i = 0; i < n; ++i) {
    f->h ^= p[i];
    f->h *= 0x100000001b3ull;
  }
}
static void fnv_double(fnv* f, double v) { fnv_bytes(f, &v, sizeof(v)); }
static void fnv_u32(fnv* f, uint32_t v) {
  const unsigned char b[4] = {(unsigned char)v, (unsigned char)(v >> 8), (unsigned char)(v >> 16),
                              (unsigned char)(v >> 24)};
  fnv_bytes(f, b, sizeof(b));
}
static void fnv_vec(fnv* f, tdo_vec3 v) {
  fnv_double(f, v.x);
  fnv_double(f, v.y);
  fnv_double(f, v.z);
}
static fnv fnv_start(void) {
  fnv f = {0xcbf29ce484222325ull};
  return f;
}

/* `platform` = 1 prints the line with an '@': path segments and samples come out of libm calls
 * (sin, cos, acos, atan2, cbrt, tan) whose last bit differs between glibc and newlib, so their bit
 * patterns are reported but not compared (docs/embedded.md); the printed digits are compared. */
static void emit_checksum(const char* what, uint32_t count, fnv f, int platform) {
  line_buf l = {{0}, 0};
  if (platform) put_str(&l, "@");
  put_str(&l, what);
  put_str(&l, " ");
  put_u32(&l, count);
  put_str(&l, " fnv1a64 ");
  put_hex64(&l, f.h);
  emit(&l);
}

static void emit_point(const char* prefix, uint32_t i, tdo_vec3 p) {
  line_buf l = {{0}, 0};
  put_str(&l, prefix);
  put_u32(&l, i);
  put_str(&l, " ");
  put_vec(&l, p);
  emit(&l);
}

/* ---- The demo ---------------------------------------------------------------------------- */

/* State of one pass over the samples (tdo_planner_each_sample). */
typedef struct sample_pass {
  fnv f;           /* checksum pass */
  uint32_t stride; /* print pass: every stride-th sample */
  uint32_t n;      /* print pass: number of samples (the last one is printed too) */
} sample_pass;

static void checksum_sample(void* user, uint32_t index, const tdo_sample* q) {
  sample_pass* pass = (sample_pass*)user;
  (void)index;
  fnv_double(&pass->f, q->t);
  fnv_vec(&pass->f, q->p);
  fnv_vec(&pass->f, q->v);
  fnv_vec(&pass->f, q->a);
}

static void print_sample(void* user, uint32_t index, const tdo_sample* q) {
  const sample_pass* pass = (const sample_pass*)user;
  line_buf l = {{0}, 0};
  if (index % pass->stride == 0u) {
    put_str(&l, "  sample t ");
    put_fixed(&l, q->t, 9);
    put_str(&l, " p ");
    put_vec(&l, q->p);
    emit(&l);
  }
  if (index + 1u == pass->n) {
    put_str(&l, "  last   t ");
    put_fixed(&l, q->t, 9);
    put_str(&l, " p ");
    put_vec(&l, q->p);
    emit(&l);
  }
}

static void print_result(const tdo_planner* planner, const tdo_plan_request* req,
                         const tdo_plan_result* r) {
  emit_u32("expansions", r->search.expansions);
  emit_fixed("search_cost_m", r->search.cost, 9);
  emit_fixed("search_penalized_cost_m", r->search.penalized_cost, 9);
  emit_u32("pivots", r->search.pivots);

  fnv f = fnv_start();
  for (uint32_t i = 0; i < r->n_grid_path; ++i) fnv_vec(&f, r->grid_path[i]);
  emit_checksum("grid_path", r->n_grid_path, f, 0);

  if (r->reached >= TDO_PLAN_CORRECT) {
    emit_u32("waypoints", r->n_waypoints);
    emit_u32("waypoints_kept_for_clearance", r->n_safety_critical);
    for (uint32_t i = 0; i < r->n_waypoints; ++i) emit_point("  wp ", i, r->waypoints[i]);
  }
  if (r->reached >= TDO_PLAN_SMOOTH) {
    f = fnv_start();
    for (uint32_t i = 0; i < r->path.n; ++i) {
      const tdo_path_segment* s = &r->path.seg[i];
      fnv_u32(&f, (uint32_t)s->kind);
      for (int k = 0; k < 4; ++k) fnv_vec(&f, s->p[k]);
      fnv_double(&f, s->length);
      fnv_double(&f, s->v_limit);
      fnv_u32(&f, (uint32_t)s->stop_at_end);
    }
    emit_checksum("path_segments", r->path.n, f, 1);
    emit_u32("path_segments", r->path.n);
    emit_fixed("path_length_m", r->path.length, 9);
  }
  if (r->reached >= TDO_PLAN_TRAJECTORY && r->n_samples > 0u) {
    /* The samples through tdo_planner_each_sample: stored or, with TDO_DEMO_STREAM_SAMPLES,
     * regenerated bit for bit; two passes (checksum first, then the printed ones). */
    sample_pass pass;
    pass.f = fnv_start();
    pass.stride = 0u;
    tdo_planner_each_sample(planner, checksum_sample, &pass);
    emit_checksum("samples", r->n_samples, pass.f, 1);
    emit_u32("samples", r->n_samples);
    /* every 2 s of flight and the last sample: t, position */
    const uint32_t stride = (uint32_t)(2.0 / req->params.dt + 0.5);
    pass.stride = stride > 0u ? stride : 1u;
    pass.n = r->n_samples;
    tdo_planner_each_sample(planner, print_sample, &pass);

    const tdo_feasibility* fe = &r->feasibility;
    emit_u32("feasible", (uint32_t)fe->ok);
    emit_fixed("max_speed_mps", fe->max_speed, 9);
    emit_fixed("max_acc_mps2", fe->max_acc, 9);
    /* Jerk is a third difference of positions over dt = 0.01 s: a last-bit difference of libm
     * (see docs/embedded.md) grows by 1/dt^3 = 1e6 to about 1e-9 m/s^3, so 6 decimals. */
    emit_fixed("max_jerk_mps3", fe->max_jerk, 6);
    emit_fixed("min_turn_radius_m", fe->min_turn_radius, 9);
    emit_fixed("min_sample_clearance_m", fe->min_clearance, 9);
    emit_u32("violations", fe->n_violations_total);
    emit_u32("refinements", r->refinements);
  }
  const tdo_metrics* m = &r->metrics;
  emit_fixed("length_m", m->length_m, 9);
  emit_u32("turns", m->turns);
  emit_fixed("total_turn_deg", m->total_turn_deg, 9);
  emit_fixed("min_clearance_m", m->min_clearance_m, 9);
  emit_fixed("avg_curvature_1pm", m->avg_curvature, 9);
  emit_fixed("smoothness", m->smoothness, 9);
  emit_fixed("energy_m2ps3", m->energy, 9);
  emit_fixed("flight_time_s", m->flight_time_s, 9);
  emit_u32("curvature_continuous", (uint32_t)m->curvature_continuous);
}

int tdo_demo_run(tdo_demo_info* info) {
  line_buf l = {{0}, 0};
  put_str(&l, "tdo-demo " TDO_DEMO_MAP_NAME " (" TDO_DEMO_MAP_FILE ")");
  emit(&l);

  /* The grid: voxel counts from the bounds, as mapio reads a .tdomap. */
  const double* b = tdo_demo_map_bounds;
  tdo_grid_desc desc;
  desc.nx = (int32_t)ceil((b[3] - b[0]) / tdo_demo_map_res - 1e-9);
  desc.ny = (int32_t)ceil((b[4] - b[1]) / tdo_demo_map_res - 1e-9);
  desc.nz = (int32_t)ceil((b[5] - b[2]) / tdo_demo_map_res - 1e-9);
  desc.res = tdo_demo_map_res;
  desc.origin.x = b[0];
  desc.origin.y = b[1];
  desc.origin.z = b[2];

  /* Capacities: the library's for this grid (27 headings: turn-penalised search), then the
   * firmware's tighter numbers for the arrays that would not fit (tdo_demo_config.h). */
  tdo_planner_config cfg;
  memset(&cfg, 0, sizeof(cfg));
  tdo_capacity_for_grid(&cfg.cap, desc.nx, desc.ny, desc.nz, TDO_DEMO_CLEARANCE / desc.res, 27u,
                        TDO_DEMO_MAX_NODES);
  cfg.cap.max_boxes = TDO_DEMO_MAP_BOXES;
  cfg.cap.dense_headings = 0u;  /* the dense heading index costs 216 bytes per voxel */
  cfg.cap.exact_heuristic = 0u; /* the retry's tables cost 24 bytes per voxel; Map1 never floods */
  cfg.cap.max_path = TDO_DEMO_MAX_PATH;
  cfg.cap.max_samples = TDO_DEMO_MAX_SAMPLES;
  cfg.cap.max_profile = TDO_DEMO_MAX_PROFILE;
  cfg.cap.max_waypoints = TDO_DEMO_MAX_WAYPOINTS;
  cfg.cap.max_violations = TDO_DEMO_MAX_VIOLATIONS;
  cfg.cap.boxes_only = 1u; /* the map is boxes: no distance field (4 bytes per voxel) */
  cfg.cap.stream_samples = TDO_DEMO_STREAM_SAMPLES;
  cfg.cap.max_open = TDO_DEMO_MAX_OPEN;
  /* the longest axis sizes the distance field's line scratch (max_voxels by default) */
  cfg.cap.max_axis = (uint32_t)(desc.nx > desc.ny ? (desc.nx > desc.nz ? desc.nx : desc.nz)
                                                  : (desc.ny > desc.nz ? desc.ny : desc.nz));

  info->arena_bytes = sizeof(tdo_demo_arena);
  info->footprint = tdo_planner_footprint(&cfg);
  info->arena_used = 0u;

  l.n = 0;
  put_str(&l, "map ");
  put_u32(&l, (uint32_t)desc.nx);
  put_str(&l, " x ");
  put_u32(&l, (uint32_t)desc.ny);
  put_str(&l, " x ");
  put_u32(&l, (uint32_t)desc.nz);
  put_str(&l, " voxels, res ");
  put_fixed(&l, desc.res, 3);
  put_str(&l, " m, ");
  put_u32(&l, TDO_DEMO_MAP_BOXES);
  put_str(&l, " boxes, clearance ");
  put_fixed(&l, TDO_DEMO_CLEARANCE, 3);
  put_str(&l, " m");
  emit(&l);
  emit_u32("cap_max_nodes", cfg.cap.max_nodes);
  emit_u32("cap_max_path", cfg.cap.max_path);
  emit_u32("cap_max_samples", cfg.cap.max_samples);
  emit_u32("cap_max_profile", cfg.cap.max_profile);

  tdo_planner* planner = NULL;
  tdo_status st = tdo_planner_init(&planner, tdo_demo_arena, sizeof(tdo_demo_arena), &cfg);
  if (st != TDO_OK) {
    l.n = 0;
    put_str(&l, "init ");
    put_str(&l, tdo_status_str(st));
    emit(&l);
    return 1;
  }
  info->arena_used = tdo_planner_arena_used(planner);

  tdo_grid* grid = tdo_planner_grid(planner);
  st = tdo_grid_reset(grid, &desc);
  for (uint32_t i = 0; i < TDO_DEMO_MAP_BOXES && st == TDO_OK; ++i)
    st = tdo_grid_add_box(grid, &tdo_demo_map_boxes[i]);
  if (st == TDO_OK) st = tdo_grid_finish(grid, TDO_DEMO_CLEARANCE);
  if (st != TDO_OK) {
    l.n = 0;
    put_str(&l, "map ");
    put_str(&l, tdo_status_str(st));
    emit(&l);
    return 1;
  }
  emit_u32("blocked_voxels", tdo_grid_blocked_count(grid));

  tdo_plan_request req;
  memset(&req, 0, sizeof(req));
  req.start = tdo_demo_map_start;
  req.goal = tdo_demo_map_goal;
  tdo_plan_params_default(&req.params);
  l.n = 0;
  put_str(&l, "start ");
  put_vec(&l, req.start);
  emit(&l);
  l.n = 0;
  put_str(&l, "goal ");
  put_vec(&l, req.goal);
  emit(&l);

  tdo_plan_result res;
  st = tdo_planner_plan(planner, &req, &res);
  l.n = 0;
  put_str(&l, "status ");
  put_str(&l, tdo_status_str(st));
  emit(&l);
  if (st == TDO_OK || st == TDO_ERR_INFEASIBLE) print_result(planner, &req, &res);
  tdo_demo_write("end\n");
  return st == TDO_OK ? 0 : 1;
}
