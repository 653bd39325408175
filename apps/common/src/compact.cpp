// The compact form of a trajectory message (compact.h).
#include "tdo_lcm/compact.h"

#include <cmath>
#include <cstdio>
#include <limits>
#include <string>

namespace tdo_lcm {
namespace {

Check need_count(const char* name, int32_t n, std::size_t size) {
  if (n >= 0 && static_cast<std::size_t>(n) == size) return {};
  return fail(Reason::count_mismatch, std::string(name) + ": count " + std::to_string(n) +
                                          ", array of " + std::to_string(size));
}

constexpr uint64_t kMaxSegments = static_cast<uint64_t>(std::numeric_limits<int32_t>::max()) / 12u;

Check segments_to_msg(const tdo_path& path, tdo::trajectory_t* t) {
  if (path.n > 0 && path.seg == nullptr)
    return fail(Reason::count_mismatch, "path: no segments for " + std::to_string(path.n));
  if (path.n > kMaxSegments)
    return fail(Reason::too_large, std::to_string(path.n) + " path segments");
  t->n_segments = static_cast<int32_t>(path.n);
  t->n_segment_points = 12 * t->n_segments;
  t->segment_kind.resize(path.n);
  t->segment_s0.resize(path.n);
  t->segment_length.resize(path.n);
  t->segment_points.assign(12u * path.n, 0.0);
  double s0 = 0.0;  // the same running sum as the library's (trajectory.cpp)
  for (uint32_t i = 0; i < path.n; ++i) {
    const tdo_path_segment& g = path.seg[i];
    t->segment_kind[i] = static_cast<int8_t>(g.kind);
    t->segment_s0[i] = s0;
    t->segment_length[i] = g.length;
    if (!std::isfinite(g.length))
      return fail(Reason::non_finite,
                  "segment " + std::to_string(i) + " length " + exact_num(g.length));
    for (int k = 0; k < 4; ++k) {
      const double xyz[3] = {g.p[k].x, g.p[k].y, g.p[k].z};
      for (int a = 0; a < 3; ++a) {
        if (!std::isfinite(xyz[a]))
          return fail(Reason::non_finite, "segment " + std::to_string(i) + " point " +
                                              std::to_string(k) + " = " + exact_num(xyz[a]));
        t->segment_points[12u * i + 3u * k + a] = xyz[a];
      }
    }
    s0 += g.length;
  }
  return {};
}

Check pieces_to_msg(const tdo_traj* traj, const tdo_traj_profile_info& info, tdo::trajectory_t* t) {
  if (info.n_pieces > static_cast<uint32_t>(std::numeric_limits<int32_t>::max()))
    return fail(Reason::too_large, std::to_string(info.n_pieces) + " profile pieces");
  const std::size_t n = info.n_pieces;
  t->n_pieces = static_cast<int32_t>(n);
  for (auto* v :
       {&t->piece_t0, &t->piece_dur, &t->piece_s0, &t->piece_v0, &t->piece_a0, &t->piece_j})
    v->resize(n);
  for (uint32_t k = 0; k < info.n_pieces; ++k) {
    tdo_traj_piece p{};
    const tdo_status st = tdo_traj_piece_at(traj, k, &p);
    if (st != TDO_OK)
      return fail(Reason::library_error, std::string("tdo_traj_piece_at: ") + tdo_status_str(st));
    const double vals[6] = {p.t0, p.dur, p.s0, p.v0, p.a0, p.j};
    for (double v : vals)
      if (!std::isfinite(v))
        return fail(Reason::non_finite, "piece " + std::to_string(k) + ": " + exact_num(v));
    t->piece_t0[k] = p.t0;
    t->piece_dur[k] = p.dur;
    t->piece_s0[k] = p.s0;
    t->piece_v0[k] = p.v0;
    t->piece_a0[k] = p.a0;
    t->piece_j[k] = p.j;
  }
  return {};
}

}  // namespace

void clear_compact(tdo::trajectory_t* t) {
  t->n_segments = 0;
  t->segment_kind.clear();
  t->segment_s0.clear();
  t->segment_length.clear();
  t->n_segment_points = 0;
  t->segment_points.clear();
  t->n_pieces = 0;
  for (auto* v :
       {&t->piece_t0, &t->piece_dur, &t->piece_s0, &t->piece_v0, &t->piece_a0, &t->piece_j})
    v->clear();
  t->duration_s = 0.0;
  t->path_length_m = 0.0;
  t->sample_count = 0;
}

Check compact_to_msg(const tdo_path& path, const tdo_traj* traj, tdo::trajectory_t* out) {
  clear_compact(out);
  tdo_traj_profile_info info{};
  const tdo_status st = tdo_traj_profile(traj, &info);
  if (st != TDO_OK)
    return fail(Reason::library_error, std::string("tdo_traj_profile: ") + tdo_status_str(st));
  if (info.n_samples > static_cast<uint32_t>(std::numeric_limits<int32_t>::max()))
    return fail(Reason::too_large, std::to_string(info.n_samples) + " samples");
  Check c = segments_to_msg(path, out);
  if (c.ok()) c = pieces_to_msg(traj, info, out);
  if (!c.ok()) {
    clear_compact(out);
    return c;
  }
  out->duration_s = info.duration;
  out->path_length_m = info.length;
  out->sample_count = static_cast<int32_t>(info.n_samples);
  return {};
}

Check compact_view(const tdo::trajectory_t& m, tdo_traj_view* out) {
  Check c = need_count("segment_kind", m.n_segments, m.segment_kind.size());
  if (c.ok()) c = need_count("segment_s0", m.n_segments, m.segment_s0.size());
  if (c.ok()) c = need_count("segment_length", m.n_segments, m.segment_length.size());
  if (c.ok()) c = need_count("segment_points", m.n_segment_points, m.segment_points.size());
  if (c.ok() && static_cast<int64_t>(m.n_segment_points) != 12 * static_cast<int64_t>(m.n_segments))
    c = fail(Reason::count_mismatch, "n_segment_points " + std::to_string(m.n_segment_points) +
                                         " is not 12 x n_segments " + std::to_string(m.n_segments));
  const struct {
    const char* name;
    const std::vector<double>* v;
  } pieces[] = {{"piece_t0", &m.piece_t0}, {"piece_dur", &m.piece_dur}, {"piece_s0", &m.piece_s0},
                {"piece_v0", &m.piece_v0}, {"piece_a0", &m.piece_a0},   {"piece_j", &m.piece_j}};
  for (const auto& p : pieces)
    if (c.ok()) c = need_count(p.name, m.n_pieces, p.v->size());
  if (!c.ok()) return c;
  *out = tdo_traj_view{m.n_segments,
                       m.segment_kind.data(),
                       m.segment_s0.data(),
                       m.segment_length.data(),
                       m.segment_points.data(),
                       m.n_pieces,
                       m.piece_t0.data(),
                       m.piece_dur.data(),
                       m.piece_s0.data(),
                       m.piece_v0.data(),
                       m.piece_a0.data(),
                       m.piece_j.data(),
                       m.duration_s,
                       m.path_length_m};
  switch (tdo_traj_check(out)) {
    case TDO_TRAJ_EVAL_OK:
      return {};
    case TDO_TRAJ_EVAL_EMPTY:
      return fail(Reason::no_plan, "no compact trajectory (" + std::to_string(m.n_segments) +
                                       " segments, " + std::to_string(m.n_pieces) + " pieces)");
    case TDO_TRAJ_EVAL_NON_FINITE:
      return fail(Reason::non_finite, "a segment, piece, duration_s or path_length_m value");
    case TDO_TRAJ_EVAL_BAD_KIND:
      return fail(Reason::bad_enum, "a segment_kind outside SEGMENT_LINE/BEZIER/ARC");
    case TDO_TRAJ_EVAL_BAD_ORDER:
      return fail(Reason::out_of_range,
                  "negative lengths or duration, piece_dur <= 0, or piece_t0 / segment_s0 "
                  "decreasing");
    case TDO_TRAJ_EVAL_NO_LENGTH:
      return fail(Reason::out_of_range, "no segment of positive length");
  }
  return fail(Reason::out_of_range, "unknown tdo_traj_check result");
}

Check samples_from_compact(const tdo::trajectory_t& m, uint32_t max_samples,
                           std::vector<tdo_sample>* out) {
  tdo_traj_view v{};
  Check c = compact_view(m, &v);
  if (!c.ok()) return c;
  if (!(m.dt > 0.0) || !std::isfinite(m.dt))
    return fail(Reason::out_of_range, "dt " + exact_num(m.dt) + " is not > 0");
  if (m.sample_count < 2)
    return fail(Reason::out_of_range, "sample_count " + std::to_string(m.sample_count) + " < 2");
  if (static_cast<uint64_t>(m.sample_count) > max_samples)
    return fail(Reason::over_capacity, std::to_string(m.sample_count) +
                                           " samples, more than the capacity of " +
                                           std::to_string(max_samples));
  out->assign(static_cast<std::size_t>(m.sample_count), tdo_sample{});
  for (int32_t i = 0; i < m.sample_count; ++i) {
    tdo_traj_state st;
    const double t = m.dt * i;  // the library's sample times
    tdo_traj_eval(&v, t, &st);
    tdo_sample& s = (*out)[static_cast<std::size_t>(i)];
    s.t = t;
    s.p = tdo_vec3{st.p[0], st.p[1], st.p[2]};
    s.v = tdo_vec3{st.v[0], st.v[1], st.v[2]};
    s.a = tdo_vec3{st.a[0], st.a[1], st.a[2]};
  }
  return {};
}

}  // namespace tdo_lcm
