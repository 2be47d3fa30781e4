// ReliefKit — maxima of a cubic form on the unit circle,
//   F(theta) = a c^3 + 3b c^2 s + 3c c s^2 + d s^3,   (c, s) = (cos theta, sin theta),
// the function maximised by the curvature gradient of demarcating curves (thesis eq. 3.3) and
// by the edge-model correlation of relief edges (eq. 4.13). Its stationary points are the roots
// of a cubic in sin^2 theta (eq. 3.6), solved in closed form; there are one or three maxima.
#pragma once

#include <cmath>

#include "reliefkit/base/curvature.h"

namespace reliefkit {

/// F as harmonics: P cos + Q sin + R cos 3theta + S sin 3theta, evaluated on unit vectors
/// (cos, sin) without trigonometric calls; a1 and a3 scale the first and third harmonics.
struct CubicHarmonics {
  double P, Q, R, S;
  explicit CubicHarmonics(const CurvatureDerivative& C)
      : P(0.75 * (C.a + C.c)), Q(0.75 * (C.b + C.d)), R(0.25 * (C.a - 3 * C.c)), S(0.25 * (3 * C.b - C.d)) {}
  static double cos3(double c) { return c * (4 * c * c - 3); }
  static double sin3(double s) { return s * (3 - 4 * s * s); }
  double f(double c, double s, double a1 = 1, double a3 = 1) const {
    return a1 * (P * c + Q * s) + a3 * (R * cos3(c) + S * sin3(s));
  }
  double df(double c, double s, double a1 = 1, double a3 = 1) const {
    return a1 * (-P * s + Q * c) + a3 * 3 * (-R * sin3(s) + S * cos3(c));
  }
  double d2f(double c, double s, double a1 = 1, double a3 = 1) const {
    return -a1 * (P * c + Q * s) - a3 * 9 * (R * cos3(c) + S * sin3(s));
  }
  double scale() const { return std::abs(P) + std::abs(Q) + std::abs(R) + std::abs(S); }
  /// The cubic form (a, b, c, d) with these harmonics.
  static CurvatureDerivative form(double P, double Q, double R, double S) {
    const double c = P / 3 - R, a = 4 * P / 3 - c, b = Q / 3 + S, d = 4 * Q / 3 - b;
    return {a, b, c, d};
  }
};

/// The maxima of F as unit vectors (cos, sin), each once; returns how many (1 or 3; 0 if F = 0).
int cubic_form_maxima(const CurvatureDerivative& C, Vec2 out[3]);

}  // namespace reliefkit
