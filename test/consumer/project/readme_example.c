#include <stdio.h>
#include <stdlib.h>

#include "tdo/tdo.h"

int main(void) {
  /* Capacities for 20 x 20 x 10 voxels, clearance/voxel edge 1, turn-penalised search. */
  tdo_planner_config cfg = {0};
  tdo_capacity_for_grid(&cfg.cap, 20, 20, 10, 1.0, 27u, 0u);
  cfg.cap.max_boxes = 16;
  size_t bytes = tdo_planner_footprint(&cfg); /* the only memory the planner ever uses */
  void* arena = malloc(bytes);
  tdo_planner* planner = NULL;
  if (arena == NULL || tdo_planner_init(&planner, arena, bytes, &cfg) != TDO_OK) return 1;

  /* Map: 10 x 10 x 5 m in 0.5 m voxels, a wall at x in [4, 5] m open at y > 7 m. */
  tdo_grid* grid = tdo_planner_grid(planner);
  tdo_grid_desc desc = {20, 20, 10, 0.5, {0.0, 0.0, 0.0}};
  tdo_box wall = {{4.0, 0.0, 0.0}, {5.0, 7.0, 5.0}};
  tdo_status st = tdo_grid_reset(grid, &desc);
  if (st == TDO_OK) st = tdo_grid_add_box(grid, &wall);
  if (st == TDO_OK) st = tdo_grid_finish(grid, 0.5); /* keep 0.5 m from every obstacle */

  /* One call: search, correction, smoothing, time parameterisation, feasibility, metrics. */
  /* Zero-initialised: the vehicle starts at rest (req.state, docs/design.md s.5). */
  tdo_plan_request req = {0};
  tdo_plan_params_default(&req.params); /* the table of tdo/params.h: tdo-plan --list-params */
  req.start = (tdo_vec3){1.0, 1.0, 1.5};
  req.goal = (tdo_vec3){9.0, 1.0, 1.5};
  tdo_plan_result res;
  if (st == TDO_OK) st = tdo_planner_plan(planner, &req, &res);
  printf("status %s\n", tdo_status_str(st));
  if (st == TDO_OK) {
    printf("waypoints %u, length %.3f m, turns %u, flight %.2f s\n", res.n_waypoints,
           res.metrics.length_m, res.metrics.turns, res.metrics.flight_time_s);
    printf("max speed %.3f m/s, acc %.3f m/s^2, jerk %.3f m/s^3, %u samples\n",
           res.feasibility.max_speed, res.feasibility.max_acc, res.feasibility.max_jerk,
           res.n_samples);
  }
  free(arena);
  return st == TDO_OK ? 0 : 1;
}
