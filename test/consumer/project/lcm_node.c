/* An LCM node built against the installed message types alone (find_package(tdo), tdo::lcmtypes):
 * it publishes a compact trajectory on memq://, receives it through its subscription, samples it
 * with tdo_traj_eval.h, and checks a plan request's use_defaults constants. Strict C99. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "tdo_plan_request_t.h"
#include "tdo_traj_eval.h"
#include "tdo_trajectory_t.h"

static int received = 0;
static double end_x = 0.0, mid_v = 0.0;

static void on_trajectory(const lcm_recv_buf_t* rbuf, const char* channel,
                          const tdo_trajectory_t* m, void* user) {
  tdo_traj_view v;
  tdo_traj_state st;
  (void)rbuf;
  (void)channel;
  (void)user;
  v.n_segments = m->n_segments;
  v.segment_kind = m->segment_kind;
  v.segment_s0 = m->segment_s0;
  v.segment_length = m->segment_length;
  v.segment_points = m->segment_points;
  v.n_pieces = m->n_pieces;
  v.piece_t0 = m->piece_t0;
  v.piece_dur = m->piece_dur;
  v.piece_s0 = m->piece_s0;
  v.piece_v0 = m->piece_v0;
  v.piece_a0 = m->piece_a0;
  v.piece_j = m->piece_j;
  v.duration = m->duration_s;
  v.length = m->path_length_m;
  if (tdo_traj_check(&v) != TDO_TRAJ_EVAL_OK) return;
  tdo_traj_eval(&v, 2.5, &st);
  mid_v = st.v[0];
  tdo_traj_eval(&v, 99.0, &st);
  end_x = st.p[0];
  ++received;
}

int main(void) {
  /* One line of 3 m along x flown in 5 s: jerk +1, -1, 0, -1, +1 for 1 s each. */
  int8_t kind[1] = {TDO_TRAJECTORY_T_SEGMENT_LINE};
  double s0[1] = {0.0}, len[1] = {3.0};
  double pts[12] = {0, 0, 1, 3, 0, 1, 0, 0, 0, 0, 0, 0};
  double t0[5] = {0, 1, 2, 3, 4}, dur[5] = {1, 1, 1, 1, 1};
  double ps0[5] = {0.0, 1.0 / 6.0, 1.0, 2.0, 2.0 + 5.0 / 6.0};
  double pv0[5] = {0.0, 0.5, 1.0, 1.0, 0.5}, pa0[5] = {0.0, 1.0, 0.0, 0.0, -1.0};
  double pj[5] = {1.0, -1.0, 0.0, -1.0, 1.0};
  tdo_trajectory_t m;
  tdo_plan_request_t r;
  lcm_t* lcm = lcm_create("memq://");
  tdo_trajectory_t_subscription_t* sub;
  int i;
  if (lcm == NULL) {
    fprintf(stderr, "lcm_create failed\n");
    return 1;
  }
  memset(&m, 0, sizeof m);
  m.status = (char*)"ok";
  m.detail = (char*)"";
  m.n_segments = 1;
  m.segment_kind = kind;
  m.segment_s0 = s0;
  m.segment_length = len;
  m.n_segment_points = 12;
  m.segment_points = pts;
  m.n_pieces = 5;
  m.piece_t0 = t0;
  m.piece_dur = dur;
  m.piece_s0 = ps0;
  m.piece_v0 = pv0;
  m.piece_a0 = pa0;
  m.piece_j = pj;
  m.duration_s = 5.0;
  m.path_length_m = 3.0;
  m.dt = 0.01;
  m.sample_count = 501;
  sub = tdo_trajectory_t_subscribe(lcm, "TDO_TRAJECTORY", on_trajectory, NULL);
  if (tdo_trajectory_t_publish(lcm, "TDO_TRAJECTORY", &m) != 0) {
    fprintf(stderr, "publish failed\n");
    tdo_trajectory_t_unsubscribe(lcm, sub);
    lcm_destroy(lcm);
    return 1;
  }
  for (i = 0; i < 10 && received == 0; ++i) lcm_handle_timeout(lcm, 100);
  tdo_trajectory_t_unsubscribe(lcm, sub); /* frees the subscription lcm_destroy leaves */
  lcm_destroy(lcm);
  memset(&r, 0, sizeof r);
  r.use_defaults = TDO_PLAN_REQUEST_T_USE_DEFAULT_ALL;
  if (received != 1 || fabs(end_x - 3.0) > 1e-12 || fabs(mid_v - 1.0) > 1e-12 ||
      r.use_defaults != 33554431) {
    fprintf(stderr, "lcm node: received %d, end x %g, v(2.5 s) %g\n", received, end_x, mid_v);
    return 1;
  }
  printf("lcm node: trajectory received and sampled (end x %g m, v %g m/s at 2.5 s)\n", end_x,
         mid_v);
  return 0;
}
