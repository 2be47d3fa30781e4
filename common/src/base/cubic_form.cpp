#include "reliefkit/base/cubic_form.h"

#include <algorithm>
#include <cmath>

namespace reliefkit {
namespace {

// Rotates the unit vector (c, s) by the angle whose cosine and sine are (cd, sd).
inline void rotate(double& c, double& s, double cd, double sd) {
  double nc = c * cd - s * sd, ns = s * cd + c * sd;
  c = nc, s = ns;
}

// Newton steps towards a maximum of the (scaled) function, on unit vectors.
inline void polish(const CubicHarmonics& h, double& c, double& s, double a1 = 1, double a3 = 1) {
  for (int it = 0; it < 3; ++it) {
    double d2 = h.d2f(c, s, a1, a3);
    if (!(d2 < 0)) return;
    double step = -h.df(c, s, a1, a3) / d2;
    if (!std::isfinite(step) || std::abs(step) > 0.3) return;
    double st2 = step * step;
    rotate(c, s, 1 - 0.5 * st2 + st2 * st2 / 24, step * (1 - st2 / 6));
    double n = std::sqrt(c * c + s * s);
    c /= n, s /= n;
  }
}

// Real roots of c3 s^3 + c2 s^2 + c1 s + c0 (any leading coefficient, incl. zero).
int real_roots(double c3, double c2, double c1, double c0, double out[3]) {
  const double scale = std::max({std::abs(c3), std::abs(c2), std::abs(c1), std::abs(c0)});
  if (!(scale > 0)) return 0;
  c3 /= scale, c2 /= scale, c1 /= scale, c0 /= scale;
  if (std::abs(c3) < 1e-12) {
    if (std::abs(c2) < 1e-12) {
      if (std::abs(c1) < 1e-12) return 0;
      out[0] = -c0 / c1;
      return 1;
    }
    double disc = c1 * c1 - 4 * c2 * c0;
    if (disc < 0) return 0;
    double sq = std::sqrt(disc);
    out[0] = (-c1 + sq) / (2 * c2);
    out[1] = (-c1 - sq) / (2 * c2);
    return 2;
  }
  // Depressed cubic t^3 + p t + q with s = t - b/3.
  double b = c2 / c3, c = c1 / c3, d = c0 / c3;
  double p = c - b * b / 3, q = 2 * b * b * b / 27 - b * c / 3 + d;
  double disc = q * q / 4 + p * p * p / 27;
  // A double root makes disc vanish; rounding must not turn it into a single real root.
  if (disc > 1e-10 * (q * q / 4 + std::abs(p * p * p) / 27) + 1e-300) {
    double sq = std::sqrt(disc);
    out[0] = std::cbrt(-q / 2 + sq) + std::cbrt(-q / 2 - sq) - b / 3;
    return 1;
  }
  double r = std::sqrt(std::max(0.0, -p / 3));
  if (r == 0) {
    out[0] = -b / 3;
    return 1;
  }
  const double phi = std::acos(std::clamp(-q / (2 * r * r * r), -1.0, 1.0)) / 3;
  const double cp = std::cos(phi), sp = std::sin(phi), h3 = 0.86602540378443865;  // sqrt(3)/2
  out[0] = 2 * r * cp - b / 3;
  out[1] = 2 * r * (-0.5 * cp - h3 * sp) - b / 3;  // phi + 120 degrees
  out[2] = 2 * r * (-0.5 * cp + h3 * sp) - b / 3;  // phi + 240 degrees
  return 3;
}

}  // namespace

// The maxima of C(v(theta)) as unit vectors (cos, sin), each once: 1 or 3 of them (0 if C = 0).
int cubic_form_maxima(const CurvatureDerivative& C, Vec2 out[3]) {
  const double a = C.a, b = C.b, c = C.c, d = C.d;
  const CubicHarmonics h(C);
  const double scale = h.scale();
  if (!(scale > 0) || !std::isfinite(scale)) return 0;
  // Eq. 3.6: cubic in x = sin^2(theta).
  const double A3 = (a - 3 * c) * (a - 3 * c) + (3 * b - d) * (3 * b - d);
  const double A2 = 2 * (2 * c - a) * (a - 3 * c) - (3 * b - d) * (3 * b - d) - 2 * b * (3 * b - d);
  const double A1 = (2 * c - a) * (2 * c - a) + 2 * b * (3 * b - d) + b * b;
  const double A0 = -b * b;
  double roots[3];
  const int n = real_roots(A3, A2, A1, A0, roots);
  // Candidates (+-sqrt(1-x), +-sqrt(x)): the stationary points are among them (squaring eq. 3.5
  // adds as many spurious ones, recognised by f' != 0). Keep the maxima, each once.
  int nmax = 0;
  auto consider = [&](double cs, double sn) {
    if (nmax == 3 || !(h.d2f(cs, sn) < 0)) return;
    double slope = std::abs(h.df(cs, sn));
    if (slope > 1e-3 * scale) return;  // spurious candidate
    if (slope > 1e-9 * scale) {        // root inexact (near a double root): Newton-polish it
      polish(h, cs, sn);
      if (std::abs(h.df(cs, sn)) > 1e-6 * scale || !(h.d2f(cs, sn) < 0)) return;
    }
    for (int i = 0; i < nmax; ++i)
      if (std::abs(out[i].x() - cs) + std::abs(out[i].y() - sn) < 1e-6) return;
    out[nmax++] = Vec2(cs, sn);
  };
  for (int i = 0; i < n; ++i) {
    const double x = roots[i];
    if (!(x >= -1e-9 && x <= 1 + 1e-9)) continue;
    const double sn = std::sqrt(std::clamp(x, 0.0, 1.0)), cs = std::sqrt(std::clamp(1 - x, 0.0, 1.0));
    consider(cs, sn);
    consider(cs, -sn);
    consider(-cs, sn);
    consider(-cs, -sn);
  }
  if (nmax == 0) {  // roots lost to rounding: the axes, polished
    for (Vec2 v : {Vec2(1, 0), Vec2(-1, 0), Vec2(0, 1), Vec2(0, -1)}) {
      double cs = v.x(), sn = v.y();
      polish(h, cs, sn);
      if (nmax == 0 || h.f(cs, sn) > h.f(out[0].x(), out[0].y())) out[0] = Vec2(cs, sn), nmax = 1;
    }
  }
  return nmax;
}

}  // namespace reliefkit
