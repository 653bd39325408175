// Path segment evaluation (path.h): arclength parameterisation of lines, arcs and cubic Beziers,
// curvature, tangent and curvature rate, checked against independent references written here
// (dense chord polylines for arclength, finite differences of positions for tangent/curvature).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <vector>

#include "rng.h"
#include "tdo/path.h"

namespace {

using tdo_test::Rng;

struct P {
  double x, y, z;
};
P of(const tdo_vec3& v) { return P{v.x, v.y, v.z}; }
P operator+(P a, P b) { return P{a.x + b.x, a.y + b.y, a.z + b.z}; }
P operator-(P a, P b) { return P{a.x - b.x, a.y - b.y, a.z - b.z}; }
P operator*(P a, double k) { return P{a.x * k, a.y * k, a.z * k}; }
double dot(P a, P b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
double norm(P a) { return std::sqrt(dot(a, a)); }
P cross(P a, P b) { return P{a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }
double dist(const tdo_vec3& a, const tdo_vec3& b) { return norm(of(a) - of(b)); }
tdo_vec3 v3(double x, double y, double z) { return tdo_vec3{x, y, z}; }

/** Bernstein form of a cubic, evaluated directly (independent of the library's de Casteljau). */
P bezier_at(const tdo_path_segment& s, double t) {
  const double u = 1.0 - t;
  return of(s.p[0]) * (u * u * u) + of(s.p[1]) * (3.0 * u * u * t) +
         of(s.p[2]) * (3.0 * u * t * t) + of(s.p[3]) * (t * t * t);
}

/** Dense chord polyline of a Bezier: cumulative chord length at t = i/n. */
std::vector<double> chord_table(const tdo_path_segment& s, int n) {
  std::vector<double> cum(static_cast<size_t>(n) + 1u, 0.0);
  P prev = bezier_at(s, 0.0);
  for (int i = 1; i <= n; ++i) {
    const P q = bezier_at(s, static_cast<double>(i) / n);
    cum[static_cast<size_t>(i)] = cum[static_cast<size_t>(i) - 1u] + norm(q - prev);
    prev = q;
  }
  return cum;
}

tdo_path_segment make_line(tdo_vec3 a, tdo_vec3 b) {
  tdo_path_segment s{};
  s.kind = TDO_SEGMENT_LINE;
  s.p[0] = a;
  s.p[1] = b;
  s.length = tdo_segment_length(&s);
  return s;
}

tdo_path_segment make_bezier(tdo_vec3 a, tdo_vec3 b, tdo_vec3 c, tdo_vec3 d) {
  tdo_path_segment s{};
  s.kind = TDO_SEGMENT_BEZIER;
  s.p[0] = a;
  s.p[1] = b;
  s.p[2] = c;
  s.p[3] = d;
  s.length = tdo_segment_length(&s);
  return s;
}

/** Arc of radius r about c in the plane spanned by unit e1, e2 from angle 0 to `sweep`. */
tdo_path_segment make_arc(P c, P e1, P e2, double r, double sweep) {
  tdo_path_segment s{};
  s.kind = TDO_SEGMENT_ARC;
  const P a = c + e1 * r;
  const P b = c + (e1 * std::cos(sweep) + e2 * std::sin(sweep)) * r;
  s.p[0] = v3(a.x, a.y, a.z);
  s.p[1] = v3(b.x, b.y, b.z);
  s.p[2] = v3(c.x, c.y, c.z);
  s.length = tdo_segment_length(&s);
  return s;
}

/** Curvature from three positions at arclength s-h, s, s+h (circumscribed circle). */
double curvature_from_points(const tdo_path_segment& seg, double s, double h) {
  const P a = of(tdo_segment_point(&seg, s - h));
  const P b = of(tdo_segment_point(&seg, s));
  const P c = of(tdo_segment_point(&seg, s + h));
  const double ab = norm(b - a), bc = norm(c - b), ca = norm(a - c);
  return 2.0 * norm(cross(b - a, c - a)) / (ab * bc * ca);
}

TEST(PathLine, GivenLineWhenEvaluatedThenPointsAreLinearInArclength) {
  // GIVEN a 3-4-12 line (length 13)
  const tdo_path_segment s = make_line(v3(1, 2, 3), v3(4, 6, 15));
  EXPECT_DOUBLE_EQ(s.length, 13.0);
  // WHEN evaluated at arclengths THEN distance from the start equals s, curvature is 0
  for (int i = 0; i <= 13; ++i) {
    const double at = i;
    EXPECT_NEAR(dist(tdo_segment_point(&s, at), s.p[0]), at, 1e-12);
    EXPECT_NEAR(dist(tdo_segment_point(&s, at), s.p[1]), 13.0 - at, 1e-12);
    EXPECT_DOUBLE_EQ(tdo_segment_curvature(&s, at), 0.0);
  }
  const tdo_vec3 t = tdo_segment_tangent(&s, 5.0);
  EXPECT_NEAR(t.x, 3.0 / 13.0, 1e-15);
  EXPECT_NEAR(t.z, 12.0 / 13.0, 1e-15);
  // AND the ends are exact, s is clamped
  const tdo_vec3 e = tdo_segment_point(&s, 100.0);
  EXPECT_EQ(0, std::memcmp(&e, &s.p[1], sizeof e));
  const tdo_vec3 b = tdo_segment_point(&s, -1.0);
  EXPECT_EQ(0, std::memcmp(&b, &s.p[0], sizeof b));
}

TEST(PathArc, GivenArcWhenEvaluatedThenOnCircleWithCurvatureOneOverR) {
  // GIVEN a tilted arc of radius 2.5 sweeping 100 degrees
  const P c{1.0, -2.0, 3.0};
  const P e1 = P{1.0, 1.0, 0.0} * (1.0 / std::sqrt(2.0));
  const P e2 = P{-1.0, 1.0, 2.0} * (1.0 / std::sqrt(6.0));
  const double r = 2.5, sweep = 100.0 * M_PI / 180.0;
  const tdo_path_segment s = make_arc(c, e1, e2, r, sweep);
  // THEN its length is r * sweep
  EXPECT_NEAR(s.length, r * sweep, 1e-12);
  // WHEN evaluated THEN every point is on the circle, at the right angle, curvature 1/r
  for (int i = 0; i <= 50; ++i) {
    const double at = s.length * i / 50.0;
    const P q = of(tdo_segment_point(&s, at)) - c;
    EXPECT_NEAR(norm(q), r, 1e-12);
    EXPECT_NEAR(std::atan2(dot(q, e2), dot(q, e1)), at / r, 1e-12);
    EXPECT_DOUBLE_EQ(tdo_segment_curvature(&s, at), 1.0 / r);
    if (i > 0 && i < 50) {
      EXPECT_NEAR(curvature_from_points(s, at, 1e-3), 1.0 / r, 1e-6);
    }
    // tangent is perpendicular to the radius and points forward
    const P t = of(tdo_segment_tangent(&s, at));
    EXPECT_NEAR(norm(t), 1.0, 1e-14);
    EXPECT_NEAR(dot(t, q), 0.0, 1e-12);
    EXPECT_GT(dot(t, cross(cross(e1, e2), q)), 0.0);
  }
  const tdo_vec3 e = tdo_segment_point(&s, s.length);
  EXPECT_EQ(0, std::memcmp(&e, &s.p[1], sizeof e));
}

TEST(PathBezier, GivenRandomCubicsWhenEvaluatedByArclengthThenMatchesDenseChordReference) {
  Rng rng(20240611u);
  for (int n = 0; n < 60; ++n) {
    // GIVEN a random, non-degenerate cubic (control points spread in a 10 m box)
    const tdo_path_segment s =
        make_bezier(v3(rng.uniform(-5, 5), rng.uniform(-5, 5), rng.uniform(-5, 5)),
                    v3(rng.uniform(-5, 5), rng.uniform(-5, 5), rng.uniform(-5, 5)),
                    v3(rng.uniform(-5, 5), rng.uniform(-5, 5), rng.uniform(-5, 5)),
                    v3(rng.uniform(-5, 5), rng.uniform(-5, 5), rng.uniform(-5, 5)));
    // THEN its length matches a 200000-chord polyline (Richardson-extrapolated: error ~h^2)
    const int kN = 100000;
    const std::vector<double> c1 = chord_table(s, kN);
    const std::vector<double> c2 = chord_table(s, 2 * kN);
    const double ref = (4.0 * c2.back() - c1.back()) / 3.0;
    ASSERT_NEAR(s.length, ref, 1e-8 * ref) << "case " << n;
    // WHEN evaluated at arclength s THEN the point lies where the chord table puts it
    for (int k = 1; k < 20; ++k) {
      const double at = s.length * k / 20.0;
      size_t i = 0;
      while (i + 1 < c2.size() && c2[i + 1] < at) ++i;
      const double f = (at - c2[i]) / (c2[i + 1] - c2[i]);
      const double t_ref = (static_cast<double>(i) + f) / (2.0 * kN);
      const P want = bezier_at(s, t_ref);
      EXPECT_LT(norm(of(tdo_segment_point(&s, at)) - want), 1e-6) << "case " << n << " k " << k;
      EXPECT_NEAR(tdo_segment_param(&s, at), t_ref, 1e-6);
    }
  }
}

TEST(PathBezier, GivenCubicWhenDifferentiatedNumericallyThenTangentCurvatureAndRateAgree) {
  Rng rng(77u);
  int checked = 0;
  for (int n = 0; n < 60; ++n) {
    // GIVEN a gently curved cubic (control points near a line, so curvature stays moderate)
    const tdo_path_segment s =
        make_bezier(v3(0, 0, 0), v3(1.0, rng.uniform(-0.6, 0.6), rng.uniform(-0.6, 0.6)),
                    v3(2.0, rng.uniform(-0.6, 0.6), rng.uniform(-0.6, 0.6)),
                    v3(3.0, rng.uniform(-0.6, 0.6), rng.uniform(-0.6, 0.6)));
    const double h = 1e-3;
    for (int k = 1; k < 10; ++k) {
      const double at = s.length * k / 10.0;
      tdo_segment_state st{};
      ASSERT_EQ(1, tdo_segment_eval(&s, at, &st));
      // unit step between nearby points: arclength parameter has unit speed
      EXPECT_NEAR(dist(tdo_segment_point(&s, at + h), tdo_segment_point(&s, at - h)), 2.0 * h,
                  1e-6 * h + st.kappa * st.kappa * h * h * h);
      // tangent = central difference of positions
      const P d =
          (of(tdo_segment_point(&s, at + h)) - of(tdo_segment_point(&s, at - h))) * (0.5 / h);
      EXPECT_LT(norm(of(st.t) - d), 1e-5);
      // curvature = circumscribed circle of three points; curvature vector = second difference
      EXPECT_NEAR(st.kappa, curvature_from_points(s, at, h), 1e-5 * (1.0 + st.kappa));
      EXPECT_NEAR(st.kappa, tdo_segment_curvature(&s, at), 1e-15);
      const P dd = (of(tdo_segment_point(&s, at + h)) + of(tdo_segment_point(&s, at - h)) -
                    of(tdo_segment_point(&s, at)) * 2.0) *
                   (1.0 / (h * h));
      EXPECT_LT(norm(of(st.kn) - dd), 1e-4 * (1.0 + st.kappa));
      // curvature rate = central difference of the curvature
      if (st.kappa > 1e-3) {
        const double dk =
            (tdo_segment_curvature(&s, at + h) - tdo_segment_curvature(&s, at - h)) / (2.0 * h);
        EXPECT_NEAR(st.dkappa_ds, dk, 1e-4 * (1.0 + std::fabs(dk)));
        ++checked;
      }
    }
  }
  EXPECT_GT(checked, 300);
}

TEST(PathBezier, GivenSameInputWhenEvaluatedTwiceThenBitIdenticalAndEndsExact) {
  const tdo_path_segment s = make_bezier(v3(0, 0, 0), v3(1, 0, 0), v3(2, 1, 0), v3(2, 2, 1));
  for (int k = 0; k <= 40; ++k) {
    const double at = s.length * k / 40.0;
    const tdo_vec3 a = tdo_segment_point(&s, at);
    const tdo_vec3 b = tdo_segment_point(&s, at);
    EXPECT_EQ(0, std::memcmp(&a, &b, sizeof a));
  }
  const tdo_vec3 e = tdo_segment_point(&s, s.length);
  EXPECT_EQ(0, std::memcmp(&e, &s.p[3], sizeof e));
  const tdo_vec3 b = tdo_segment_point(&s, 0.0);
  EXPECT_EQ(0, std::memcmp(&b, &s.p[0], sizeof b));
}

TEST(PathLocate, GivenPathWhenLocatingArclengthThenSegmentAndLocalOffset) {
  tdo_path_segment segs[3] = {make_line(v3(0, 0, 0), v3(2, 0, 0)),
                              make_line(v3(2, 0, 0), v3(2, 3, 0)),
                              make_line(v3(2, 3, 0), v3(2, 3, 1))};
  const tdo_path p{segs, 3u, 6.0};
  double ls = -1.0;
  EXPECT_EQ(0u, tdo_path_locate(&p, -5.0, &ls));
  EXPECT_DOUBLE_EQ(ls, 0.0);
  EXPECT_EQ(0u, tdo_path_locate(&p, 1.5, &ls));
  EXPECT_DOUBLE_EQ(ls, 1.5);
  EXPECT_EQ(1u, tdo_path_locate(&p, 2.0, &ls));
  EXPECT_DOUBLE_EQ(ls, 0.0);
  EXPECT_EQ(2u, tdo_path_locate(&p, 5.5, &ls));
  EXPECT_DOUBLE_EQ(ls, 0.5);
  EXPECT_EQ(2u, tdo_path_locate(&p, 99.0, &ls));
  EXPECT_DOUBLE_EQ(ls, 1.0);
  EXPECT_EQ(UINT32_MAX, tdo_path_locate(nullptr, 1.0, &ls));
}

TEST(PathDegenerate, GivenNullOrNonFiniteWhenEvaluatedThenSafeValues) {
  EXPECT_DOUBLE_EQ(tdo_segment_length(nullptr), 0.0);
  EXPECT_DOUBLE_EQ(tdo_segment_curvature(nullptr, 0.0), 0.0);
  tdo_segment_state st{};
  EXPECT_EQ(0, tdo_segment_eval(nullptr, 0.0, &st));
  tdo_path_segment s = make_line(v3(0, 0, 0), v3(std::nan(""), 0, 0));
  EXPECT_DOUBLE_EQ(s.length, 0.0);
  tdo_path_segment z = make_line(v3(1, 1, 1), v3(1, 1, 1));
  EXPECT_EQ(0, tdo_segment_eval(&z, 0.0, &st));
  EXPECT_DOUBLE_EQ(st.p.x, 1.0);
}

}  // namespace
