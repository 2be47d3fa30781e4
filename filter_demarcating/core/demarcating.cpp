#include "demarcating.h"

#include <algorithm>
#include <cmath>
#include <complex>

#include "reliefkit/memory.h"

namespace reliefkit {
namespace {

constexpr double kPi = 3.14159265358979323846;

// C(v(theta)) = a c^3 + 3b c^2 s + 3c c s^2 + d s^3 as harmonics:
// P cos + Q sin + R cos 3theta + S sin 3theta.
struct Harmonics {
  double P, Q, R, S;
  explicit Harmonics(const CurvatureDerivative& C)
      : P(0.75 * (C.a + C.c)), Q(0.75 * (C.b + C.d)), R(0.25 * (C.a - 3 * C.c)), S(0.25 * (3 * C.b - C.d)) {}
  double f(double t, double a1 = 1, double a3 = 1) const {
    return a1 * (P * std::cos(t) + Q * std::sin(t)) + a3 * (R * std::cos(3 * t) + S * std::sin(3 * t));
  }
  double df(double t, double a1 = 1, double a3 = 1) const {
    return a1 * (-P * std::sin(t) + Q * std::cos(t)) + a3 * 3 * (-R * std::sin(3 * t) + S * std::cos(3 * t));
  }
  double d2f(double t, double a1 = 1, double a3 = 1) const {
    return -a1 * (P * std::cos(t) + Q * std::sin(t)) - a3 * 9 * (R * std::cos(3 * t) + S * std::sin(3 * t));
  }
};

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
  double phi = std::acos(std::clamp(-q / (2 * r * r * r), -1.0, 1.0));
  for (int k = 0; k < 3; ++k) out[k] = 2 * r * std::cos((phi + 2 * kPi * k) / 3) - b / 3;
  return 3;
}

// Newton polishing of a stationary point of h.f (scaled by a1, a3).
double polish(const Harmonics& h, double t, double a1 = 1, double a3 = 1) {
  for (int it = 0; it < 4; ++it) {
    double d2 = h.d2f(t, a1, a3);
    if (!(d2 < 0)) break;  // only climb maxima
    double step = -h.df(t, a1, a3) / d2;
    if (!std::isfinite(step) || std::abs(step) > 0.3) break;
    t += step;
  }
  return t;
}

}  // namespace

double curvature_gradient_angle(const CurvatureDerivative& C, double sigma, bool* competing) {
  const double a = C.a, b = C.b, c = C.c, d = C.d;
  const Harmonics h(C);
  // Eq. 3.6: cubic in s = sin^2(theta).
  const double A3 = (a - 3 * c) * (a - 3 * c) + (3 * b - d) * (3 * b - d);
  const double A2 = 2 * (2 * c - a) * (a - 3 * c) - (3 * b - d) * (3 * b - d) - 2 * b * (3 * b - d);
  const double A1 = (2 * c - a) * (2 * c - a) + 2 * b * (3 * b - d) + b * b;
  const double A0 = -b * b;
  double roots[3];
  int n = real_roots(A3, A2, A1, A0, roots);
  // Candidate angles: +-asin(sqrt(s)) and their supplements; the maxima of C(v(theta)) are
  // among them (squaring eq. 3.5 only adds candidates). theta = 0 covers b = 0 exactly.
  double maxima[12];
  int nmax = 0;
  auto consider = [&](double t) {
    t = polish(h, t);
    if (!(h.d2f(t) < 0) || std::abs(h.df(t)) > 1e-6 * (std::abs(h.P) + std::abs(h.Q) + std::abs(h.R) + std::abs(h.S)))
      return;
    t = std::remainder(t, 2 * kPi);
    for (int i = 0; i < nmax; ++i)
      if (std::abs(std::remainder(maxima[i] - t, 2 * kPi)) < 1e-6) return;
    maxima[nmax++] = t;
  };
  for (int i = 0; i < n; ++i) {
    double s = roots[i];
    if (!(s >= -1e-9 && s <= 1 + 1e-9)) continue;
    double th = std::asin(std::sqrt(std::clamp(s, 0.0, 1.0)));
    for (double t : {th, -th, kPi - th, kPi + th}) consider(t);
  }
  if (nmax == 0) {
    consider(0.0);
    consider(kPi);
  }
  if (nmax == 0) {  // C == 0 (or not finite): no gradient; any direction
    if (competing) *competing = false;
    return 0;
  }
  if (competing) *competing = nmax >= 3;
  if (nmax < 3) {
    int best = 0;
    for (int i = 1; i < nmax; ++i)
      if (h.f(maxima[i]) > h.f(maxima[best])) best = i;
    return maxima[best];
  }
  // Three maxima: smooth with a Gaussian in theta (harmonic k scaled by exp(-k^2 sigma^2 / 2))
  // and pick the maximum whose smoothed peak is highest.
  const double a1 = std::exp(-0.5 * sigma * sigma), a3 = std::exp(-4.5 * sigma * sigma);
  int best = 0;
  double best_val = -1e300;
  for (int i = 0; i < nmax; ++i) {
    double t = maxima[i];
    for (int k = -8; k <= 8; ++k) {  // climb the smoothed function (coarse search, then Newton)
      double u = maxima[i] + k * (kPi / 64);
      if (h.f(u, a1, a3) > h.f(t, a1, a3)) t = u;
    }
    t = polish(h, t, a1, a3);
    double v = h.f(t, a1, a3);
    if (v > best_val + 1e-12 * std::abs(best_val) || (std::abs(v - best_val) <= 1e-12 * std::abs(best_val) &&
                                                      h.f(maxima[i]) > h.f(maxima[best]))) {
      best_val = v;
      best = i;
    }
  }
  return maxima[best];
}

CurvatureGradient curvature_gradient(const Curvature& c) {
  const int nv = static_cast<int>(c.k1.size());
  if (c.dcurv.size() != c.k1.size()) throw InputError("demarcating curves need the curvature derivative tensor");
  CurvatureGradient g;
  sized(g.direction, size_t(nv), Vec3(Vec3::Zero()));
  sized(g.kappa, size_t(nv));
  sized(g.strength, size_t(nv));
  long long competing = 0;
#pragma omp parallel for schedule(static) reduction(+ : competing)
  for (int v = 0; v < nv; ++v) {
    bool comp = false;
    double t = curvature_gradient_angle(c.dcurv[v], kCompetingMaximaSigma, &comp);
    competing += comp;
    double ct = std::cos(t), st = std::sin(t);
    g.direction[v] = ct * c.dir1[v] + st * c.dir2[v];
    g.kappa[v] = c.k1[v] * ct * ct + c.k2[v] * st * st;
    g.strength[v] = std::max(0.0, c.dcurv[v].along(ct, st));
  }
  g.competing = competing;
  return g;
}

double median_strength(const CurvatureGradient& g) {
  std::vector<double> s;
  s.reserve(g.strength.size());
  for (double x : g.strength)
    if (std::isfinite(x) && x > 0) s.push_back(x);
  if (s.empty()) return 0;
  auto mid = s.begin() + s.size() / 2;
  std::nth_element(s.begin(), mid, s.end());
  return *mid;
}

Polylines demarcating_curves(const TriMesh& mesh, const Curvature& c, const CurvatureGradient& g,
                             const DemarcatingOptions& opt) {
  DirectionalField field;
  field.direction = g.direction;
  field.value = g.kappa;
  field.strength = g.strength;
  field.axial = false;  // g_p is a vector: opposite gradients are inconsistent
  field.value_along = [&c](int v, const Vec3& t) { return c.normal_curvature(v, t); };
  field.strength_along = [&c](int v, const Vec3& t) { return std::max(0.0, c.derivative_along(v, t)); };
  ZeroCrossingOptions zo;
  zo.max_angle = opt.max_angle;
  zo.min_strength = opt.min_strength;
  Polylines p = extract_zero_crossings(mesh, c.normal, field, zo);
  return opt.min_length > 0 ? drop_short_chains(p, opt.min_length) : p;
}

double automatic_strength_threshold(double median_vertex_strength, const Polylines& all) {
  std::vector<double> st;
  st.reserve(all.segments.size());
  for (const auto& sg : all.segments) st.push_back(0.5 * (all.strength[sg[0]] + all.strength[sg[1]]));
  double top = 0;
  if (!st.empty()) {
    auto k = st.begin() + static_cast<long>(kTopPercentile * double(st.size() - 1));
    std::nth_element(st.begin(), k, st.end());
    top = *k;
  }
  return std::max(kNoiseFactor * median_vertex_strength, kTopFactor * top);
}

DemarcatingResult compute_demarcating(const TriMesh& mesh, const DemarcatingParams& p) {
  require_triangles(mesh);
  DemarcatingResult r;
  r.mean_edge = edge_length_stats(mesh).mean;
  r.presmoothing = p.presmoothing >= 0 ? p.presmoothing : DemarcatingParams::kDefaultPresmoothingEdges * r.mean_edge;
  r.min_length = p.min_length >= 0 ? p.min_length : DemarcatingParams::kDefaultMinLengthEdges * r.mean_edge;
  CurvatureOptions co;
  co.estimator = p.estimator;
  co.smoothing_scale = r.presmoothing;
  co.derivatives = true;
  co.progress = p.progress;
  r.curvature = compute_curvature(mesh, co);
  if (p.progress) p.progress(85, "Curvature gradient");
  r.gradient = curvature_gradient(r.curvature);
  r.median_strength = median_strength(r.gradient);
  if (p.progress) p.progress(92, "Demarcating curves");
  DemarcatingOptions o;
  o.min_strength = 0;
  o.max_angle = p.max_angle;
  Polylines all = demarcating_curves(mesh, r.curvature, r.gradient, o);
  r.automatic_threshold = automatic_strength_threshold(r.median_strength, all);
  r.threshold = p.relative_threshold * r.automatic_threshold;
  r.curves = drop_short_chains(keep_strong_segments(all, r.threshold), r.min_length);
  return r;
}

std::vector<double> mean_curvature_shading(const Curvature& c, double contrast) {
  const size_t nv = c.k1.size();
  std::vector<double> h(nv), absh;
  absh.reserve(nv);
  for (size_t v = 0; v < nv; ++v) {
    h[v] = 0.5 * (c.k1[v] + c.k2[v]);
    if (std::isfinite(h[v]) && h[v] != 0) absh.push_back(std::abs(h[v]));
  }
  double ref = 1;
  if (!absh.empty()) {
    auto k = absh.begin() + static_cast<long>(0.9 * double(absh.size() - 1));
    std::nth_element(absh.begin(), k, absh.end());
    if (*k > 0) ref = *k;
  }
  for (auto& x : h) x = std::isfinite(x) ? 0.5 + std::atan(contrast * x / ref) / kPi : 0.5;
  return h;
}

void darken_along_curves(const TriMesh& mesh, const Polylines& curves, double amount, std::vector<double>& grey) {
  const double keep = std::clamp(1.0 - amount, 0.0, 1.0);
  std::vector<char> mark(grey.size(), 0);
  for (int f : curves.segment_face)
    for (int v : mesh.faces[f]) mark[v] = 1;
  for (size_t v = 0; v < grey.size(); ++v)
    if (mark[v]) grey[v] *= keep;
}

}  // namespace reliefkit
