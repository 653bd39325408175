// The G2 corner shape of the smoothing (smooth.cpp, docs/design.md s.3), internal: tangent length
// per metre of radius (tau) and the curvature-rate constant (rate = max|dkappa/ds| r^2) of the
// unit corner, by sampling and golden-section refinement, and a cheap bound of that rate.
#ifndef TDO_SRC_G2_SHAPE_H
#define TDO_SRC_G2_SHAPE_H

namespace tdo_internal {

// Yang-Sukkarieh constants, c1 derived exactly (smooth.cpp's header comment).
constexpr double kC2 = 0.5797958971132712392789;   // 2 (sqrt(6) - 1) / 5
constexpr double kC1 = (kC2 + 1.0) * (kC2 + 4.0);  // 7.2351427678757392...
constexpr double kC3 = (kC2 + 4.0) / (kC1 + 6.0);  // 0.3460329803339428...
constexpr double kQ = 1.0 - kC3 * (1.0 + kC2);     // 0.4533385174025598... = 6 c3 / (c2 + 4)

/** Tangent length per metre of radius of the Yang-Sukkarieh corner with half-deflection beta. */
double g2_tau(double beta);

/** max |dkappa/ds| r^2 of the Yang-Sukkarieh corner (a corner of radius r: g2_rate / r^2). */
double g2_rate(double beta);

/**
 * tau and rate of the G2 corner whose inner control points sit at fractions gf, hf of the
 * tangent length, half-deflection beta (beta in (0, pi/2), gf, hf > 0, gf + hf < 1).
 */
void g2_shape(double beta, double gf, double hf, double* tau, double* rate);

/**
 * Lower bounds of g2_shape(beta, gf, hf)'s tau and of tau^2 rate (its max|dkappa/ds| at tangent
 * length 1), up to rounding: the best of every step-th sample it refines (step 1: about a third
 * of its cost; step divides 32).
 */
void g2_shape_lower(double beta, double gf, double hf, double* tau_lower, double* f_lower,
                    int step = 1);

/**
 * A lower bound of the rate g2_shape(beta, gf, hf) gives, bit for bit (its *rate is never
 * smaller): a few of its own curvature-rate samples over an interval bound of the peak curvature.
 * Costs about a third of g2_shape. 0 when no bound is found.
 */
double g2_rate_lower(double beta, double gf, double hf);

/**
 * A looser lower bound of the same rate, bit for bit as sound: the rate samples at t = 0 and 1
 * over the curvature bound on 2 intervals instead of 16. About a sixth of g2_rate_lower's cost;
 * it decides where the rate lies far above what the caller asks (the common case).
 */
double g2_rate_lower_quick(double beta, double gf, double hf);

}  // namespace tdo_internal

#endif  // TDO_SRC_G2_SHAPE_H
