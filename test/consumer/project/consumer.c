/* A C program using the installed libtdo: plan around a wall in a 10 x 10 x 10 m grid. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "tdo/tdo.h"

int main(void) {
  if (strcmp(tdo_status_str(TDO_ERR_START_BLOCKED), "start_blocked") != 0) {
    fprintf(stderr, "unexpected status name %s\n", tdo_status_str(TDO_ERR_START_BLOCKED));
    return 1;
  }

  /* Capacities: 10 x 10 x 10 voxels, no clearance, no heading costs, 16 boxes; then the arena. */
  tdo_planner_config cfg;
  memset(&cfg, 0, sizeof cfg);
  tdo_capacity_for_grid(&cfg.cap, 10, 10, 10, 0.0, 1u, 0u);
  cfg.cap.max_boxes = 16;
  size_t bytes = tdo_planner_footprint(&cfg);
  void* arena = malloc(bytes);
  tdo_planner* planner = NULL;
  tdo_status st = arena ? tdo_planner_init(&planner, arena, bytes, &cfg) : TDO_ERR_ARENA_TOO_SMALL;
  if (bytes == 0 || st != TDO_OK) {
    fprintf(stderr, "init: %s (footprint %zu bytes)\n", tdo_status_str(st), bytes);
    free(arena);
    return 1;
  }

  /* Map: 1 m voxels from the origin, one wall at x in [4, 5] m leaving a gap at y > 8 m. */
  tdo_grid* grid = tdo_planner_grid(planner);
  tdo_grid_desc desc = {10, 10, 10, 1.0, {0.0, 0.0, 0.0}};
  tdo_box wall = {{4.0, 0.0, 0.0}, {5.0, 8.0, 10.0}};
  st = tdo_grid_reset(grid, &desc);
  if (st == TDO_OK) st = tdo_grid_add_box(grid, &wall);
  if (st == TDO_OK) st = tdo_grid_finish(grid, 0.0);

  /* Query: bidirectional A*, no penalties, configured expansion budget. */
  tdo_search_input in;
  memset(&in, 0, sizeof in);
  in.grid = grid;
  in.start = (tdo_vec3){1.5, 1.5, 1.5};
  in.goal = (tdo_vec3){8.5, 1.5, 1.5};
  in.kind = TDO_SEARCH_BIDIR;
  tdo_search_output out;
  if (st == TDO_OK) st = tdo_search_run(tdo_planner_search(planner), &in, &out);
  if (st != TDO_OK) {
    fprintf(stderr, "plan: %s\n", tdo_status_str(st));
    free(arena);
    return 1;
  }
  printf("%s: %u voxels, %.3f m, %u expansions, arena %zu bytes\n", tdo_status_str(st), out.n_path,
         out.cost, out.expansions, bytes);

  /* Known answer (no corner cutting): the detour through the gap is 11 + 5 sqrt(2) m, 16 steps. */
  double err = out.cost - 18.0710678118654752;
  if (err < 0.0) err = -err;
  const tdo_voxel* last = &out.path[out.n_path - 1];
  int ok = err < 1e-6 && out.n_path == 17 && out.path[0].i == 1 && out.path[0].j == 1 &&
           out.path[0].k == 1 && last->i == 8 && last->j == 1 && last->k == 1;
  if (!ok) fprintf(stderr, "unexpected path: cost %.9f m, %u voxels\n", out.cost, out.n_path);
  free(arena);
  return ok ? 0 : 1;
}
