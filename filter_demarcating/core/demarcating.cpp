#include "demarcating.h"

#include <algorithm>
#include <cmath>
#include <complex>

#include "reliefkit/memory.h"

namespace reliefkit {
namespace {

constexpr double kPi = 3.14159265358979323846;

// C(v(theta)) = a c^3 + 3b c^2 s + 3c c s^2 + d s^3 as harmonics:
// P cos + Q sin + R cos 3theta + S sin 3theta, evaluated on unit vectors (cos, sin) without
// trigonometric calls; a1 and a3 scale the first and third harmonic (Gaussian smoothing).
struct Harmonics {
  double P, Q, R, S;
  explicit Harmonics(const CurvatureDerivative& C)
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
};

// Rotates the unit vector (c, s) by the angle whose cosine and sine are (cd, sd).
inline void rotate(double& c, double& s, double cd, double sd) {
  double nc = c * cd - s * sd, ns = s * cd + c * sd;
  c = nc, s = ns;
}

// Newton steps towards a maximum of the (scaled) function, on unit vectors.
inline void polish(const Harmonics& h, double& c, double& s, double a1 = 1, double a3 = 1) {
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
static int maxima_of(const CurvatureDerivative& C, Vec2 out[3]) {
  const double a = C.a, b = C.b, c = C.c, d = C.d;
  const Harmonics h(C);
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

Vec2 curvature_gradient_direction(const CurvatureDerivative& C, double sigma, bool* competing) {
  if (competing) *competing = false;
  Vec2 m[3];
  const int n = maxima_of(C, m);
  if (n == 0) return Vec2(1, 0);  // C == 0: no gradient, any direction
  const Harmonics h(C);
  int best = 0;
  for (int i = 1; i < n; ++i)
    if (h.f(m[i].x(), m[i].y()) > h.f(m[best].x(), m[best].y())) best = i;
  if (n < 3) return m[best];
  if (competing) *competing = true;
  // Three maxima: smooth C(v(theta)) with a Gaussian in theta (harmonic k scaled by
  // exp(-k^2 sigma^2 / 2)); close maxima merge, the larger weighing more. The maximum of C
  // nearest to the global maximum of the smoothed function is g_p.
  const double a1 = std::exp(-0.5 * sigma * sigma), a3 = std::exp(-4.5 * sigma * sigma);
  const double P = a1 * h.P, Q = a1 * h.Q, R = a3 * h.R, S = a3 * h.S;
  const double cs = P / 3 - R, as = 4 * P / 3 - cs, bs = Q / 3 + S, ds = 4 * Q / 3 - bs;
  const CurvatureDerivative smoothed{as, bs, cs, ds};
  Vec2 ms[3];
  const int ns = maxima_of(smoothed, ms);
  if (ns == 0) return m[best];
  const Harmonics hs(smoothed);
  int top = 0;
  for (int i = 1; i < ns; ++i)
    if (hs.f(ms[i].x(), ms[i].y()) > hs.f(ms[top].x(), ms[top].y())) top = i;
  int nearest = 0;
  for (int i = 1; i < n; ++i)
    if (m[i].dot(ms[top]) > m[nearest].dot(ms[top])) nearest = i;
  return m[nearest];
}

double curvature_gradient_angle(const CurvatureDerivative& C, double sigma, bool* competing) {
  Vec2 v = curvature_gradient_direction(C, sigma, competing);
  return std::atan2(v.y(), v.x());
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
    Vec2 dir = curvature_gradient_direction(c.dcurv[v], kCompetingMaximaSigma, &comp);
    competing += comp;
    const double ct = dir.x(), st = dir.y();
    g.direction[v] = ct * c.dir1[v] + st * c.dir2[v];
    g.kappa[v] = c.k1[v] * ct * ct + c.k2[v] * st * st;
    g.strength[v] = std::max(0.0, c.dcurv[v].along(ct, st));
  }
  g.competing = competing;
  return g;
}

double median_strength(const CurvatureGradient& g) { return median_positive(g.strength); }

Polylines demarcating_curves(const TriMesh& mesh, const Curvature& c, const CurvatureGradient& g,
                             const DemarcatingOptions& opt) {
  DirectionalFieldView field;
  field.direction = g.direction.data();
  field.value = g.kappa.data();
  field.strength = g.strength.data();
  field.size = g.direction.size();
  field.axial = false;  // g_p is a vector: opposite gradients are inconsistent
  field.value_along = [&c](int v, const Vec3& t) { return c.normal_curvature(v, t); };
  field.strength_along = [&c](int v, const Vec3& t) { return std::max(0.0, c.derivative_along(v, t)); };
  ZeroCrossingOptions zo;
  zo.max_angle = opt.max_angle;
  zo.min_strength = opt.min_strength;
  Polylines p = extract_zero_crossings(mesh, c.normal, field, zo);
  return opt.min_length > 0 ? drop_short_chains(p, opt.min_length) : p;
}

DemarcatingResult compute_demarcating(const TriMesh& mesh, const DemarcatingParams& p) {
  require_triangles(mesh);
  DemarcatingResult r;
  r.mean_edge = mean_edge_length(mesh);
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
  r.automatic_threshold = automatic_curve_threshold(r.median_strength, all);
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
