#include "reliefkit/base/angles.h"
#include "reliefkit/multiscale/scale_selection.h"

#include <algorithm>
#include <cmath>

namespace reliefkit {

namespace {
}

double ridge_optimal_scale(double t0, double gamma) { return 2 * gamma * t0 / (3 - 2 * gamma); }

double relief_edge_optimal_scale_unit_step(double t0, double g) {
  const double A = 2 * g - 6 * kPi * t0 + 8 * kPi * g * t0 + 1;
  const double B = std::sqrt(4 * g * g + 40 * kPi * g * t0 + 4 * g + 36 * kPi * kPi * t0 * t0 - 12 * kPi * t0 + 1);
  const double C = 4 * (3 * kPi - 2 * kPi * g);
  return (A + B) / C;
}

double relief_edge_optimal_scale(double t0, double gamma) { return 2 * gamma * t0 / (3 - 2 * gamma); }

double select_scale(const std::vector<double>& t, const double* f, int stride, double gamma) {
  const int n = static_cast<int>(t.size());
  int best = -1;
  double best_v = 0;
  for (int k = 0; k < n; ++k) {
    const double v = std::pow(t[k], gamma) * f[size_t(k) * size_t(stride)];
    if (std::isfinite(v) && v > best_v) best_v = v, best = k;
  }
  if (best < 0) return 0;
  if (best == 0 || best == n - 1) return t[best];
  // Parabola through (log t, log of the normalised strength) at best-1, best, best+1.
  auto at = [&](int k) { return std::log(std::pow(t[k], gamma) * f[size_t(k) * size_t(stride)]); };
  const double x0 = std::log(t[best - 1]), x1 = std::log(t[best]), x2 = std::log(t[best + 1]);
  const double y0 = at(best - 1), y1 = at(best), y2 = at(best + 1);
  if (!std::isfinite(y0) || !std::isfinite(y2)) return t[best];
  const double d01 = (y1 - y0) / (x1 - x0), d12 = (y2 - y1) / (x2 - x1), curv = (d12 - d01) / (x2 - x0);
  if (!(curv < 0)) return t[best];
  // Newton form p(x) = y0 + d01 (x - x0) + curv (x - x0)(x - x1): its vertex.
  const double xs = 0.5 * (x0 + x1) - d01 / (2 * curv);
  return std::exp(std::clamp(xs, x0, x2));
}

ScaleBracket bracket_scale(const std::vector<double>& u, double x) {
  const int n = static_cast<int>(u.size());
  ScaleBracket b;
  while (b.lower + 2 < n && u[b.lower + 1] < x) ++b.lower;
  b.upper = std::min(b.lower + 1, n - 1);
  const double span = u[b.upper] - u[b.lower];
  b.weight = span > 0 ? std::clamp((x - u[b.lower]) / span, 0.0, 1.0) : 0.0;
  return b;
}

}  // namespace reliefkit
