// Benchmark map generator. See mapgen.h.
#include "mapgen.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <memory>
#include <new>
#include <queue>
#include <sstream>

#include "tdo/tdo.h"
#include "tdo_io/map_io.h"

namespace tdo_mapgen {

// ------------------------------------------------------------------------------------ random

uint64_t splitmix64(uint64_t* state) {
  uint64_t z = (*state += 0x9E3779B97F4A7C15ull);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}

Rng::Rng(uint64_t seed, uint64_t stream) {
  // Mix the stream into the seed through one splitmix64 step, then fill the state.
  uint64_t mix = seed;
  const uint64_t a = splitmix64(&mix);
  uint64_t st = a ^ (stream * 0xD1B54A32D192ED03ull) ^ 0x74646F6D61706765ull;  // "tdomapge"
  for (uint64_t& w : s_) w = splitmix64(&st);
}

static uint64_t rotl(uint64_t x, int k) { return (x << k) | (x >> (64 - k)); }

uint64_t Rng::next() {
  const uint64_t result = rotl(s_[1] * 5u, 7) * 9u;
  const uint64_t t = s_[1] << 17;
  s_[2] ^= s_[0];
  s_[3] ^= s_[1];
  s_[1] ^= s_[2];
  s_[0] ^= s_[3];
  s_[2] ^= t;
  s_[3] = rotl(s_[3], 45);
  return result;
}

uint64_t Rng::below(uint64_t n) {
  // Rejection of the top partial block: every residue equally likely.
  const uint64_t limit = ~uint64_t{0} - (~uint64_t{0} % n);
  uint64_t x = next();
  while (x >= limit) x = next();
  return x % n;
}

int64_t Rng::range(int64_t lo, int64_t hi) {
  return lo + static_cast<int64_t>(below(static_cast<uint64_t>(hi - lo) + 1u));
}

// ------------------------------------------------------------------------------------ text

std::string fixed_text(int64_t v, int decimals) {
  int64_t scale = 1;
  for (int i = 0; i < decimals; ++i) scale *= 10;
  const bool neg = v < 0;
  const uint64_t a = neg ? static_cast<uint64_t>(-(v + 1)) + 1u : static_cast<uint64_t>(v);
  const uint64_t whole = a / static_cast<uint64_t>(scale);
  uint64_t frac = a % static_cast<uint64_t>(scale);
  std::string s = (neg && a != 0) ? "-" : "";
  s += std::to_string(whole);
  if (frac != 0) {
    std::string f = std::to_string(frac);
    f.insert(0, static_cast<std::size_t>(decimals) - f.size(), '0');
    while (!f.empty() && f.back() == '0') f.pop_back();
    s += "." + f;
  }
  return s;
}

namespace {

constexpr int32_t kDm = 1000;  // 0.1 mm units per dm
constexpr int64_t kM = 10000;  // 0.1 mm units per m

std::string dm_text(int32_t v) { return fixed_text(v, 1); }
std::string u_text(int64_t v) { return fixed_text(v, 4); }  // 0.1 mm -> m
std::string mm_text(int64_t v) { return fixed_text(v, 3); }

tdo_vec3 u_to_vec(const int64_t u[3]) {
  return tdo_vec3{static_cast<double>(u[0]) / kM, static_cast<double>(u[1]) / kM,
                  static_cast<double>(u[2]) / kM};
}

/** Squared distance (0.1 mm^2) from point `p` (0.1 mm) to box `b` (dm). */
int64_t dist2_u(const BoxDm& b, const int64_t p[3]) {
  int64_t d2 = 0;
  for (int a = 0; a < 3; ++a) {
    const int64_t lo = static_cast<int64_t>(b.lo[a]) * kDm;
    const int64_t hi = static_cast<int64_t>(b.hi[a]) * kDm;
    const int64_t d = p[a] < lo ? lo - p[a] : (p[a] > hi ? p[a] - hi : 0);
    d2 += d * d;
  }
  return d2;
}

/** The box keeps the free margin around start and goal. */
bool keeps_margin(const Params& p, const BoxDm& b) {
  const int64_t m = static_cast<int64_t>(p.margin_mm) * 10;
  return dist2_u(b, p.start) >= m * m && dist2_u(b, p.goal) >= m * m;
}

BoxDm box_dm(int32_t x0, int32_t y0, int32_t z0, int32_t x1, int32_t y1, int32_t z1) {
  return BoxDm{{x0, y0, z0}, {x1, y1, z1}};
}

// ------------------------------------------------------------------------------------ layouts

/** Map1: three walls and five columns laid by hand (metres x 10). */
std::vector<BoxDm> hand_layout() {
  return {box_dm(60, 0, 0, 70, 130, 160),       // wall along y next to the start, 16 m high
          box_dm(90, 90, 0, 200, 100, 80),      // low wall along x, 8 m high: fly over it
          box_dm(130, 120, 0, 140, 200, 140),   // wall along y before the goal, 14 m high
          box_dm(30, 80, 0, 50, 100, 120),      // column 2 x 2 m
          box_dm(100, 30, 0, 110, 40, 180),     // column 1 x 1 m
          box_dm(150, 40, 0, 170, 60, 105),     // column 2 x 2 m
          box_dm(90, 150, 0, 110, 170, 65),     // column 2 x 2 m, low
          box_dm(160, 130, 0, 170, 140, 200)};  // column 1 x 1 m, full height
}

/** Draw one column; false after too many attempts to keep the start/goal margin. */
bool draw_column(const Params& p, Rng* rng, BoxDm* out) {
  const int32_t fmin = p.footprint_dm[0];
  const int32_t fmax = p.footprint_dm[1];
  // Whole-metre footprints and positions when both bounds are whole metres (exact at 1 m voxels).
  const bool whole = fmin % 10 == 0 && fmax % 10 == 0;
  const int32_t step = whole ? 10 : 1;
  for (int attempt = 0; attempt < 10000; ++attempt) {
    int32_t lo[2];
    int32_t hi[2];
    for (int a = 0; a < 2; ++a) {
      const int32_t w = static_cast<int32_t>(rng->range(fmin / step, fmax / step)) * step;
      const int32_t room = p.size[a] * 10 - w;
      lo[a] = static_cast<int32_t>(rng->range(0, room / step)) * step;
      hi[a] = lo[a] + w;
    }
    // Height uniform in [1 m, map height] in 0.1 m steps.
    const int32_t h = static_cast<int32_t>(rng->range(10, static_cast<int64_t>(p.size[2]) * 10));
    const BoxDm b = box_dm(lo[0], lo[1], 0, hi[0], hi[1], h);
    if (keeps_margin(p, b)) {
      *out = b;
      return true;
    }
  }
  return false;
}

bool columns_layout(const Params& p, Rng* rng, std::vector<BoxDm>* boxes, std::string* error) {
  for (uint32_t i = 0; i < p.columns; ++i) {
    BoxDm b{};
    if (!draw_column(p, rng, &b)) {
      *error = "cannot place column " + std::to_string(i + 1) + " outside the free margin of " +
               mm_text(p.margin_mm) + " m around start and goal (map too small?)";
      return false;
    }
    boxes->push_back(b);
  }
  return true;
}

/**
 * Map4: nine full-height walls along x (1 m thick, at y = 5, 10, ..., 45) with two doors each
 * (3 m wide, a lintel above), split into segments 1-3 m long; the ten corridors between them hold
 * pillars against the walls, hanging beams and low barriers spanning the corridor, up to 500
 * obstacles in all, none within 1 m of a door. Gaps are at least 3 m wide (doors, beside
 * pillars) and 4 m high (between a
 * beam and a barrier within 4 m), so the corridors stay open at clearances somewhat above 0.5 m.
 */
bool corridors_layout(const Params& p, Rng* rng, std::vector<BoxDm>* boxes, std::string* error) {
  const int32_t X = p.size[0] * 10;
  const int32_t Z = p.size[2] * 10;
  const int32_t total = static_cast<int32_t>(p.columns);
  const int32_t n_walls = 9;
  const int32_t kDoor = 30;    // dm: 3 m doors stay passable up to a clearance of 1 m
  std::vector<int32_t> doors;  // dm, x of the doors, two per wall
  for (int32_t w = 0; w < n_walls; ++w) {
    const int32_t y0 = (w + 1) * 50;
    int32_t door[2];
    door[0] = static_cast<int32_t>(rng->range(2, 21)) * 10;
    door[1] = static_cast<int32_t>(rng->range(27, 45)) * 10;
    doors.push_back(door[0]);
    doors.push_back(door[1]);
    int32_t x = 0;
    for (int d = 0; d <= 2; ++d) {
      const int32_t end = d < 2 ? door[d] : X;
      while (x < end) {
        const int32_t len = std::min<int32_t>(static_cast<int32_t>(rng->range(1, 3)) * 10, end - x);
        boxes->push_back(box_dm(x, y0, 0, x + len, y0 + 10, Z));
        x += len;
      }
      if (d < 2) {
        const int32_t top = static_cast<int32_t>(rng->range(80, 140));
        boxes->push_back(box_dm(door[d], y0, top, door[d] + kDoor, y0 + 10, Z));
        x = door[d] + kDoor;
      }
    }
  }
  const int32_t walls = static_cast<int32_t>(boxes->size());
  if (walls > total) {
    *error = "corridor walls alone need " + std::to_string(walls) + " obstacles, more than " +
             std::to_string(total);
    return false;
  }
  // Per corridor and x (m): highest low barrier and lowest hanging beam, to keep 4 m between.
  const int32_t n_corr = n_walls + 1;
  const int32_t nx = p.size[0];
  std::vector<int32_t> low_top(static_cast<std::size_t>(n_corr * nx), 0);
  std::vector<int32_t> hang_bottom(static_cast<std::size_t>(n_corr * nx), Z);
  // Nothing stands within 1 m of a door's x range in the corridors on either side of it.
  const auto near_door = [&](int32_t c, int32_t x0, int32_t x1) {
    for (int32_t w = c - 1; w <= c; ++w) {
      if (w < 0 || w >= n_walls) continue;
      for (int d = 0; d < 2; ++d) {
        const int32_t dx = doors[static_cast<std::size_t>(2 * w + d)];
        if (x1 > dx - 10 && x0 < dx + kDoor + 10) return true;
      }
    }
    return false;
  };
  for (int32_t r = 0; r < total - walls; ++r) {
    const int32_t c = r % n_corr;
    const int32_t ylo = c == 0 ? 0 : c * 50 + 10;
    const int32_t yhi = c == n_walls ? p.size[1] * 10 : (c + 1) * 50;
    bool placed = false;
    for (int attempt = 0; attempt < 10000 && !placed; ++attempt) {
      const int64_t kind = rng->range(0, 9);
      BoxDm b{};
      std::size_t slot = 0;
      if (kind <= 3) {  // pillar against a wall, 1-2 m along it, 1 m deep, 2 m to full height
        const int32_t fx = static_cast<int32_t>(rng->range(1, 2)) * 10;
        const int32_t x0 = static_cast<int32_t>(rng->range(0, (X - fx) / 10)) * 10;
        const int32_t y0 = rng->range(0, 1) == 0 ? ylo : yhi - 10;
        const int32_t fy = 10;
        const int32_t h = static_cast<int32_t>(rng->range(20, Z));
        b = box_dm(x0, y0, 0, x0 + fx, y0 + fy, h);
      } else {
        const int32_t xi = static_cast<int32_t>(rng->range(0, nx - 1));
        slot = static_cast<std::size_t>(c * nx + xi);
        // Within 4 m along the corridor, a beam and a barrier leave at least 4 m between them.
        int32_t near_low = 0;
        int32_t near_hang = Z;
        for (int32_t x = std::max(0, xi - 4); x <= std::min(nx - 1, xi + 4); ++x) {
          near_low = std::max(near_low, low_top[static_cast<std::size_t>(c * nx + x)]);
          near_hang = std::min(near_hang, hang_bottom[static_cast<std::size_t>(c * nx + x)]);
        }
        if (kind <= 6) {  // hanging beam across the corridor, bottom at 6-16 m
          const int32_t bottom = static_cast<int32_t>(rng->range(60, 160));
          if (bottom - near_low < 40) continue;
          b = box_dm(xi * 10, ylo, bottom, xi * 10 + 10, yhi, Z);
        } else {  // low barrier across the corridor, 2-12 m high
          const int32_t top = static_cast<int32_t>(rng->range(20, 120));
          if (near_hang - top < 40) continue;
          b = box_dm(xi * 10, ylo, 0, xi * 10 + 10, yhi, top);
        }
      }
      if (!keeps_margin(p, b) || near_door(c, b.lo[0], b.hi[0])) continue;
      if (kind > 3) {
        if (kind <= 6) {
          hang_bottom[slot] = std::min(hang_bottom[slot], b.lo[2]);
        } else {
          low_top[slot] = std::max(low_top[slot], b.hi[2]);
        }
      }
      boxes->push_back(b);
      placed = true;
    }
    if (!placed) {
      *error = "cannot place corridor obstacle " + std::to_string(r + 1);
      return false;
    }
  }
  return true;
}

// ------------------------------------------------------------------------------------ movers

/** Point at arc length `s` along `pts`, and the unit tangent there. */
void point_at(const std::vector<tdo_vec3>& pts, double s, tdo_vec3* p, tdo_vec3* t) {
  double acc = 0.0;
  for (std::size_t i = 1; i < pts.size(); ++i) {
    const tdo_vec3 a = pts[i - 1];
    const tdo_vec3 b = pts[i];
    const tdo_vec3 d{b.x - a.x, b.y - a.y, b.z - a.z};
    const double len = std::sqrt(d.x * d.x + d.y * d.y + d.z * d.z);
    if (len <= 0.0) continue;
    if (acc + len >= s || i + 1 == pts.size()) {
      const double u = std::min(1.0, std::max(0.0, (s - acc) / len));
      *p = tdo_vec3{a.x + u * d.x, a.y + u * d.y, a.z + u * d.z};
      *t = tdo_vec3{d.x / len, d.y / len, d.z / len};
      return;
    }
    acc += len;
  }
  *p = pts.empty() ? tdo_vec3{0, 0, 0} : pts.back();
  *t = tdo_vec3{1, 0, 0};
}

double polyline_length(const std::vector<tdo_vec3>& pts) {
  double len = 0.0;
  for (std::size_t i = 1; i < pts.size(); ++i) {
    const double dx = pts[i].x - pts[i - 1].x;
    const double dy = pts[i].y - pts[i - 1].y;
    const double dz = pts[i].z - pts[i - 1].z;
    len += std::sqrt(dx * dx + dy * dy + dz * dz);
  }
  return len;
}

/** Largest time (0.1 s) the mover may run backwards from `cross` (0.1 mm) and stay inside. */
int64_t room_ds(const Params& p, const int64_t cross[3], const int32_t vel[3], int32_t radius) {
  int64_t best = 1000000;
  for (int a = 0; a < 3; ++a) {
    if (vel[a] == 0) continue;
    const int64_t lo = static_cast<int64_t>(radius) * 10;
    const int64_t hi = static_cast<int64_t>(p.size[a]) * kM - lo;
    // position(t) = cross - vel * t, in 0.1 mm with vel in mm/s and t in 0.1 s: cross - vel*t_ds.
    const int64_t room = vel[a] > 0 ? cross[a] - lo : hi - cross[a];
    const int64_t speed = vel[a] > 0 ? vel[a] : -static_cast<int64_t>(vel[a]);
    best = std::min(best, room <= 0 ? 0 : room / speed);
  }
  return best;
}

/**
 * Movers cross the route in its middle part (arc length 30-70 %), roughly across it (horizontal,
 * within about 27 degrees of the perpendicular), timed to pass the crossing point when a UAV at the
 * nominal speed would: t = arc / route_speed (earlier when the bounds leave too little room).
 */
void make_movers(const Params& p, const std::vector<tdo_vec3>& route, std::vector<MoverOut>* out) {
  Rng rng(p.seed, kMoverStreamBase);
  const double total = polyline_length(route);
  const uint32_t m = p.movers;
  for (uint32_t i = 0; i < m; ++i) {
    MoverOut mv{};
    mv.id = static_cast<int>(i + 1);
    const int64_t frac_milli = 300 + (400 * static_cast<int64_t>(i) + rng.range(0, 399)) / m;
    const double s = total * static_cast<double>(frac_milli) / 1000.0;
    tdo_vec3 pt{};
    tdo_vec3 tan{};
    point_at(route, s, &pt, &tan);
    int64_t cross[3] = {std::llround(pt.x * kM), std::llround(pt.y * kM), std::llround(pt.z * kM)};
    // Horizontal perpendicular to the tangent, skewed by up to +-0.5 along it.
    double hx = -tan.y;
    double hy = tan.x;
    double hn = std::sqrt(hx * hx + hy * hy);
    if (hn < 1e-6) {
      hx = 1.0;
      hy = 0.0;
      hn = 1.0;
    }
    hx /= hn;
    hy /= hn;
    const double skew = static_cast<double>(rng.range(-500, 500)) / 1000.0;
    double dx = hx + skew * tan.x;
    double dy = hy + skew * tan.y;
    const double dn = std::sqrt(dx * dx + dy * dy);
    dx /= dn;
    dy /= dn;
    const int64_t speed = rng.range(p.mover_speed_mm[0], p.mover_speed_mm[1]);
    mv.radius = static_cast<int32_t>(rng.range(p.mover_radius_mm[0], p.mover_radius_mm[1]));
    const bool flip = rng.range(0, 1) == 1;
    const int64_t want_ds = std::llround(10.0 * s * 1000.0 / p.route_speed_mm);
    int32_t best_vel[3] = {0, 0, 0};
    int64_t best_room = -1;
    // Try the drawn direction first, the opposite one when the bounds leave more room there.
    for (int k = 0; k < 2; ++k) {
      const double sign = ((k == 0) != flip) ? 1.0 : -1.0;
      const int32_t vel[3] = {
          static_cast<int32_t>(std::llround(sign * dx * static_cast<double>(speed))),
          static_cast<int32_t>(std::llround(sign * dy * static_cast<double>(speed))), 0};
      const int64_t room = room_ds(p, cross, vel, mv.radius);
      if (room > best_room) {
        best_room = room;
        std::copy(vel, vel + 3, best_vel);
      }
      if (room >= want_ds) break;
    }
    const int64_t t_ds = std::min(want_ds, best_room);
    for (int a = 0; a < 3; ++a) {
      mv.vel[a] = best_vel[a];
      mv.pos[a] = cross[a] - static_cast<int64_t>(best_vel[a]) * t_ds;
    }
    mv.cross = u_to_vec(cross);
    mv.t_cross = static_cast<double>(t_ds) / 10.0;
    mv.route_arc = s;
    mv.time_clipped = t_ds < want_ds;
    out->push_back(mv);
  }
}

// ------------------------------------------------------------------------------------ the file

std::string describe(const Params& p) {
  if (p.name == "map1")
    return "Map1 of docs/design.md s.9: 20 x 20 x 20 m, hand-laid walls and columns, sparse";
  if (p.name == "map2")
    return "Map2 of docs/design.md s.9: 20 x 20 x 20 m, 100 random columns, moderate";
  if (p.name == "map3") {
    return "Map3 of docs/design.md s.9: 20 x 20 x 20 m, 100 random columns with larger footprints, "
           "dense";
  }
  if (p.name == "map4")
    return "Map4 of docs/design.md s.9: 50 x 50 x 20 m, 500 obstacles as corridors";
  if (p.name == "map5")
    return "Map5 of docs/design.md s.9: 50 x 50 x 20 m, 500 random columns, cluttered";
  if (p.name == "map6") {
    return "Map6 of docs/design.md s.9: Map5's columns plus " + std::to_string(p.movers) +
           " moving spheres crossing the route, dynamic";
  }
  return "random map: " + std::to_string(p.size[0]) + " x " + std::to_string(p.size[1]) + " x " +
         std::to_string(p.size[2]) + " m, " + std::to_string(p.columns) + " random columns" +
         (p.movers > 0 ? ", " + std::to_string(p.movers) + " movers" : std::string());
}

std::string map_text(const Params& p, uint64_t stream, const std::vector<BoxDm>& boxes,
                     const std::vector<MoverOut>& movers) {
  std::ostringstream o;
  o << "# " << describe(p) << "\n";
  o << "# Regenerate (byte for byte): " << regenerate_command(p) << "\n";
  if (p.layout != Layout::Hand) {
    o << "# Draw stream " << stream
      << ": the first stream whose map libtdo's bidirectional search solves at clearance "
      << mm_text(p.clearance_mm) << " m.\n";
  }
  if (p.layout == Layout::Columns) {
    o << "# Columns: boxes from z = 0, footprint " << dm_text(p.footprint_dm[0]) << "-"
      << dm_text(p.footprint_dm[1]) << " m, height 1-" << p.size[2]
      << " m in 0.1 m steps, none within " << mm_text(p.margin_mm) << " m of start or goal.\n";
  } else if (p.layout == Layout::Corridors) {
    o << "# Corridors: 9 full-height walls along x (y = 5, 10, ..., 45), two 3 m doors each with "
         "a\n"
         "# lintel, in 1-3 m segments; pillars against the walls, hanging beams and low barriers\n"
         "# across the corridors, none within 1 m of a door.\n";
  }
  if (!movers.empty()) {
    o << "# Movers cross the route (a shortest grid path at clearance " << mm_text(p.clearance_mm)
      << " m) at 30-70 % of its length when a\n# UAV flying it at " << mm_text(p.route_speed_mm)
      << " m/s would be there; each line's comment gives the crossing point and time.\n";
  }
  o << "tdomap 1\n";
  o << "bounds 0 0 0 " << p.size[0] << " " << p.size[1] << " " << p.size[2] << "\n";
  o << "resolution " << mm_text(p.resolution_mm) << "\n";
  o << "start " << u_text(p.start[0]) << " " << u_text(p.start[1]) << " " << u_text(p.start[2])
    << "\n";
  o << "goal " << u_text(p.goal[0]) << " " << u_text(p.goal[1]) << " " << u_text(p.goal[2]) << "\n";
  for (const BoxDm& b : boxes) {
    o << "box " << dm_text(b.lo[0]) << " " << dm_text(b.lo[1]) << " " << dm_text(b.lo[2]) << "  "
      << dm_text(b.hi[0]) << " " << dm_text(b.hi[1]) << " " << dm_text(b.hi[2]) << "\n";
  }
  for (const MoverOut& m : movers) {
    const int64_t cross[3] = {std::llround(m.cross.x * kM), std::llround(m.cross.y * kM),
                              std::llround(m.cross.z * kM)};
    o << "mover " << m.id << "  " << u_text(m.pos[0]) << " " << u_text(m.pos[1]) << " "
      << u_text(m.pos[2]) << "  " << mm_text(m.vel[0]) << " " << mm_text(m.vel[1]) << " "
      << mm_text(m.vel[2]) << "  " << mm_text(m.radius) << "  # crosses (" << u_text(cross[0])
      << ", " << u_text(cross[1]) << ", " << u_text(cross[2])
      << ") at t = " << fixed_text(std::llround(m.t_cross * 10.0), 1) << " s"
      << (m.time_clipped ? " (early: bounds)" : "") << "\n";
  }
  return o.str();
}

bool write_text(const std::string& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  if (!out) return false;
  out << text;
  out.flush();
  return static_cast<bool>(out);
}

// ------------------------------------------------------------------------------------ own A*

/** Shortest 26-connected path over the grid's unblocked voxels, no corner cutting. */
bool own_astar(const tdo_grid* grid, const tdo_vec3& start, const tdo_vec3& goal,
               std::vector<tdo_vec3>* route, double* cost) {
  const tdo_grid_desc d = tdo_grid_get_desc(grid);
  tdo_voxel s{};
  tdo_voxel g{};
  if (tdo_grid_world_to_voxel(grid, start, &s) == 0 || tdo_grid_world_to_voxel(grid, goal, &g) == 0)
    return false;
  if (tdo_grid_is_blocked(grid, s) != 0 || tdo_grid_is_blocked(grid, g) != 0) return false;
  const int64_t nx = d.nx;
  const int64_t ny = d.ny;
  const int64_t n = nx * ny * d.nz;
  const auto index = [&](const tdo_voxel& v) { return (v.k * ny + v.j) * nx + v.i; };
  const auto voxel = [&](int64_t idx) {
    return tdo_voxel{static_cast<int32_t>(idx % nx), static_cast<int32_t>((idx / nx) % ny),
                     static_cast<int32_t>(idx / (nx * ny))};
  };
  std::vector<uint8_t> free(static_cast<std::size_t>(n));
  for (int64_t i = 0; i < n; ++i)
    free[static_cast<std::size_t>(i)] = tdo_grid_is_blocked(grid, voxel(i)) == 0 ? 1 : 0;
  const auto is_free = [&](int32_t i, int32_t j, int32_t k) {
    if (i < 0 || j < 0 || k < 0 || i >= d.nx || j >= d.ny || k >= d.nz) return false;
    return free[static_cast<std::size_t>((k * ny + j) * nx + i)] != 0;
  };
  const double step[4] = {0.0, d.res, d.res * std::sqrt(2.0), d.res * std::sqrt(3.0)};
  const auto heur = [&](const tdo_voxel& v) {
    const double dx = std::abs(v.i - g.i);
    const double dy = std::abs(v.j - g.j);
    const double dz = std::abs(v.k - g.k);
    return d.res * std::sqrt(dx * dx + dy * dy + dz * dz);
  };
  struct Entry {
    double f;
    double h;
    int64_t idx;
    bool operator<(const Entry& o) const {  // priority_queue pops the largest: invert
      if (f < o.f || f > o.f) return f > o.f;
      if (h < o.h || h > o.h) return h > o.h;
      return idx > o.idx;
    }
  };
  std::vector<double> gcost(static_cast<std::size_t>(n), HUGE_VAL);
  std::vector<int64_t> parent(static_cast<std::size_t>(n), -1);
  std::vector<uint8_t> closed(static_cast<std::size_t>(n), 0);
  std::priority_queue<Entry> open;
  const int64_t si = index(s);
  const int64_t gi = index(g);
  gcost[static_cast<std::size_t>(si)] = 0.0;
  open.push(Entry{heur(s), heur(s), si});
  bool found = false;
  while (!open.empty()) {
    const Entry e = open.top();
    open.pop();
    if (closed[static_cast<std::size_t>(e.idx)] != 0) continue;
    closed[static_cast<std::size_t>(e.idx)] = 1;
    if (e.idx == gi) {
      found = true;
      break;
    }
    const tdo_voxel v = voxel(e.idx);
    const double gv = gcost[static_cast<std::size_t>(e.idx)];
    for (int dz = -1; dz <= 1; ++dz) {
      for (int dy = -1; dy <= 1; ++dy) {
        for (int dx = -1; dx <= 1; ++dx) {
          const int axes = (dx != 0) + (dy != 0) + (dz != 0);
          if (axes == 0) continue;
          bool ok = true;  // every voxel of the 2x2(x2) block spanned by the step is free
          for (int c = 0; c <= (dz != 0 ? 1 : 0) && ok; ++c)
            for (int b = 0; b <= (dy != 0 ? 1 : 0) && ok; ++b)
              for (int a = 0; a <= (dx != 0 ? 1 : 0) && ok; ++a)
                ok = is_free(v.i + a * dx, v.j + b * dy, v.k + c * dz);
          if (!ok) continue;
          const tdo_voxel w{v.i + dx, v.j + dy, v.k + dz};
          const int64_t wi = index(w);
          const double gw = gv + step[axes];
          if (gw < gcost[static_cast<std::size_t>(wi)]) {
            gcost[static_cast<std::size_t>(wi)] = gw;
            parent[static_cast<std::size_t>(wi)] = e.idx;
            const double h = heur(w);
            open.push(Entry{gw + h, h, wi});
          }
        }
      }
    }
  }
  if (!found) return false;
  std::vector<tdo_vec3> rev;
  for (int64_t i = gi; i >= 0; i = parent[static_cast<std::size_t>(i)])
    rev.push_back(tdo_grid_voxel_center(grid, voxel(i)));
  route->assign(rev.rbegin(), rev.rend());
  if (route->size() == 1) route->push_back(goal);
  route->front() = start;
  route->back() = goal;
  *cost = gcost[static_cast<std::size_t>(gi)];
  return true;
}

}  // namespace

// ------------------------------------------------------------------------------------ API

const std::vector<std::string>& preset_names() {
  static const std::vector<std::string> names = {"map1", "map2", "map3", "map4", "map5", "map6"};
  return names;
}

bool preset(const std::string& name, Params* out) {
  Params p;
  p.name = name;
  const bool small = name == "map1" || name == "map2" || name == "map3";
  const bool large = name == "map4" || name == "map5" || name == "map6";
  if (!small && !large) return false;
  if (small) {
    p.size[0] = p.size[1] = p.size[2] = 20;
    const int64_t s[3] = {2 * kM, 2 * kM, 3 * kM};
    const int64_t g[3] = {19 * kM, 19 * kM, 10 * kM};
    std::copy(s, s + 3, p.start);
    std::copy(g, g + 3, p.goal);
  } else {
    p.size[0] = p.size[1] = 50;
    p.size[2] = 20;
    const int64_t s[3] = {2 * kM, 2 * kM, 3 * kM};
    const int64_t g[3] = {49 * kM, 49 * kM, 15 * kM};
    std::copy(s, s + 3, p.start);
    std::copy(g, g + 3, p.goal);
  }
  if (name == "map1") {
    p.layout = Layout::Hand;
  } else if (name == "map2") {
    p.columns = 100;
    p.footprint_dm[0] = 10;
    p.footprint_dm[1] = 20;
    p.seed = 2;
  } else if (name == "map3") {
    p.columns = 100;
    p.footprint_dm[0] = 20;
    p.footprint_dm[1] = 30;
    p.seed = 3;
  } else if (name == "map4") {
    p.layout = Layout::Corridors;
    p.columns = 500;
    p.seed = 4;
  } else {  // map5, and map6 = map5's columns (same seed) plus movers
    p.columns = 500;
    p.footprint_dm[0] = 10;
    p.footprint_dm[1] = 30;
    p.seed = 5;
    if (name == "map6") p.movers = 12;
  }
  *out = p;
  return true;
}

std::string validate(const Params& p) {
  for (int a = 0; a < 3; ++a) {
    if (p.size[a] < 2 || p.size[a] > 10000)
      return "--size: each size must be a whole number of metres in [2, 10000]";
  }
  if (p.resolution_mm <= 0 || p.resolution_mm > 10000)
    return "--resolution must be in (0, 10] m (steps of 1 mm)";
  const double nvox = static_cast<double>(p.size[0]) * p.size[1] * p.size[2] /
                      std::pow(p.resolution_mm / 1000.0, 3);
  if (nvox > 5e7) return "--size/--resolution: grid of more than 50,000,000 voxels";
  if (p.footprint_dm[0] < 1 || p.footprint_dm[1] < p.footprint_dm[0])
    return "--footprint needs 0.1 <= MIN <= MAX (m, steps of 0.1 m)";
  if (p.footprint_dm[1] > std::min(p.size[0], p.size[1]) * 10)
    return "--footprint MAX must fit inside the map (at most the smaller horizontal size)";
  if (p.columns > 1000000) return "--columns must be at most 1000000";
  if (p.movers > 10000) return "--movers must be at most 10000";
  if (p.mover_speed_mm[0] <= 0 || p.mover_speed_mm[1] < p.mover_speed_mm[0])
    return "--mover-speed needs 0 < MIN <= MAX (m/s, steps of 1 mm/s)";
  if (p.mover_radius_mm[0] <= 0 || p.mover_radius_mm[1] < p.mover_radius_mm[0])
    return "--mover-radius needs 0 < MIN <= MAX (m, steps of 1 mm)";
  for (int a = 0; a < 3; ++a) {
    const int64_t hi = static_cast<int64_t>(p.size[a]) * kM;
    if (p.start[a] <= 0 || p.start[a] >= hi) return "--start must lie strictly inside the bounds";
    if (p.goal[a] <= 0 || p.goal[a] >= hi) return "--goal must lie strictly inside the bounds";
  }
  if (p.start[0] == p.goal[0] && p.start[1] == p.goal[1] && p.start[2] == p.goal[2])
    return "--start and --goal are the same point";
  if (p.margin_mm < 0) return "--margin must be >= 0";
  if (p.clearance_mm < 0 || p.clearance_mm > 100000) return "--clearance must be in [0, 100] m";
  if (p.max_streams < 1) return "--max-streams must be >= 1";
  return "";
}

std::string regenerate_command(const Params& p) {
  if (!p.name.empty()) return "tdo-mapgen --map " + p.name + " -o maps/" + p.name + ".tdomap";
  std::ostringstream o;
  o << "tdo-mapgen --random --size " << p.size[0] << " " << p.size[1] << " " << p.size[2]
    << " --columns " << p.columns << " --footprint " << dm_text(p.footprint_dm[0]) << " "
    << dm_text(p.footprint_dm[1]) << " --seed " << p.seed;
  if (p.movers > 0) {
    o << " --movers " << p.movers << " --mover-speed " << mm_text(p.mover_speed_mm[0]) << " "
      << mm_text(p.mover_speed_mm[1]) << " --mover-radius " << mm_text(p.mover_radius_mm[0]) << " "
      << mm_text(p.mover_radius_mm[1]);
  }
  o << " --start " << u_text(p.start[0]) << " " << u_text(p.start[1]) << " " << u_text(p.start[2])
    << " --goal " << u_text(p.goal[0]) << " " << u_text(p.goal[1]) << " " << u_text(p.goal[2]);
  if (p.resolution_mm != 1000) o << " --resolution " << mm_text(p.resolution_mm);
  if (p.margin_mm != 1500) o << " --margin " << mm_text(p.margin_mm);
  if (p.clearance_mm != 500) o << " --clearance " << mm_text(p.clearance_mm);
  o << " -o FILE";
  return o.str();
}

bool check_map(const std::string& path, double clearance, const tdo_vec3* start,
               const tdo_vec3* goal, double resolution, bool want_route, Check* out,
               std::string* error) {
  *out = Check{};
  tdo_io::Map map;
  tdo_io::LoadOptions opts;
  opts.resolution = resolution;
  if (!tdo_io::load_map(path, opts, &map, error)) return false;
  if (start == nullptr && !map.has_start) {
    *error = path + ": no start given and the map has none";
    return false;
  }
  if (goal == nullptr && !map.has_goal) {
    *error = path + ": no goal given and the map has none";
    return false;
  }
  const tdo_vec3 s = start != nullptr ? *start : map.start;
  const tdo_vec3 g = goal != nullptr ? *goal : map.goal;
  tdo_planner_config cfg{};
  cfg.cap = tdo_io::capacity_for(map, clearance, 1u, 0u);
  const std::size_t bytes = tdo_planner_footprint(&cfg);
  if (bytes == 0) {
    *error = path + ": invalid planner configuration for this map";
    return false;
  }
  std::unique_ptr<unsigned char[]> arena(new (std::nothrow) unsigned char[bytes]);
  if (!arena) {
    *error = path + ": cannot allocate a planner arena of " + std::to_string(bytes) + " bytes";
    return false;
  }
  tdo_planner* planner = nullptr;
  tdo_status st = tdo_planner_init(&planner, arena.get(), bytes, &cfg);
  if (st != TDO_OK) {
    *error = path + ": planner init: " + tdo_status_str(st);
    return false;
  }
  tdo_grid* grid = tdo_planner_grid(planner);
  st = tdo_io::load_into(map, grid, clearance);
  if (st != TDO_OK) {
    *error = path + ": loading the map into libtdo: " + tdo_status_str(st);
    return false;
  }
  const tdo_grid_desc d = tdo_grid_get_desc(grid);
  out->dims[0] = d.nx;
  out->dims[1] = d.ny;
  out->dims[2] = d.nz;
  out->res = d.res;
  out->voxels = static_cast<uint64_t>(d.nx) * d.ny * d.nz;
  out->blocked = tdo_grid_blocked_count(grid);
  out->boxes = map.boxes.size();
  out->cubes = map.voxels.size();
  for (int32_t k = 0; k < d.nz; ++k)
    for (int32_t j = 0; j < d.ny; ++j)
      for (int32_t i = 0; i < d.nx; ++i)
        out->occupied += tdo_grid_is_occupied(grid, tdo_voxel{i, j, k}) != 0 ? 1u : 0u;

  tdo_search_input in{};
  in.grid = grid;
  in.start = s;
  in.goal = g;
  in.kind = TDO_SEARCH_BIDIR;
  tdo_search_output res{};
  st = tdo_search_run(tdo_planner_search(planner), &in, &res);
  out->status = static_cast<int>(st);
  out->solved = st == TDO_OK;
  if (out->solved) out->length = res.cost;
  if (want_route && out->solved) {
    if (!own_astar(grid, s, g, &out->route, &out->route_length)) {
      *error = path + ": libtdo's bidirectional search found a path, the generator's A* did not";
      return false;
    }
    if (std::fabs(out->route_length - out->length) > 1e-6 * std::max(1.0, out->length)) {
      char buf[160];
      std::snprintf(buf, sizeof buf, "libtdo's bidirectional cost %.9f differs from A* cost %.9f",
                    out->length, out->route_length);
      *error = path + ": " + buf;
      return false;
    }
  }
  return true;
}

bool generate(const Params& p, const std::string& scratch_path, Result* out, std::string* error) {
  *out = Result{};
  const std::string bad = validate(p);
  if (!bad.empty()) {
    *error = bad;
    return false;
  }
  const double clearance = p.clearance_mm / 1000.0;
  // tdo_io picks the reader by extension.
  const std::string ext = ".tdomap";
  const bool has_ext = scratch_path.size() >= ext.size() &&
                       scratch_path.compare(scratch_path.size() - ext.size(), ext.size(), ext) == 0;
  const std::string scratch = has_ext ? scratch_path : scratch_path + ext;
  const uint64_t streams = p.layout == Layout::Hand ? 1u : p.max_streams;
  for (uint64_t stream = 0; stream < streams; ++stream) {
    std::vector<BoxDm> boxes;
    Rng rng(p.seed, stream);
    bool ok = true;
    if (p.layout == Layout::Hand) {
      boxes = hand_layout();
    } else if (p.layout == Layout::Corridors) {
      ok = corridors_layout(p, &rng, &boxes, error);
    } else {
      ok = columns_layout(p, &rng, &boxes, error);
    }
    if (!ok) return false;
    const std::string text = map_text(p, stream, boxes, {});
    if (!write_text(scratch, text)) {
      *error = scratch + ": cannot write";
      return false;
    }
    Check check;
    const bool loaded =
        check_map(scratch, clearance, nullptr, nullptr, 0.0, p.movers > 0, &check, error);
    std::remove(scratch.c_str());
    if (!loaded) return false;
    if (!check.solved) continue;
    out->stream = stream;
    out->boxes = boxes;
    out->check = check;
    if (p.movers > 0) make_movers(p, check.route, &out->movers);
    out->text = map_text(p, stream, boxes, out->movers);
    return true;
  }
  *error = "no solvable map in " + std::to_string(streams) +
           " draw streams (bidirectional search at clearance " + mm_text(p.clearance_mm) +
           " m); the map is too dense";
  return false;
}

}  // namespace tdo_mapgen
