#include "reliefkit/base/angles.h"
#include "reliefkit/demarcating/demarcating.h"
#include "reliefkit/base/curve_selection.h"

#include <algorithm>
#include <cmath>
#include <complex>

#include "reliefkit/base/cubic_form.h"
#include "reliefkit/base/memory.h"
#include "reliefkit/base/noise_patch.h"

namespace reliefkit {
namespace {


}  // namespace

Vec2 curvature_gradient_direction(const CurvatureDerivative& C, double sigma, bool* competing) {
  if (competing) *competing = false;
  Vec2 m[3];
  const int n = cubic_form_maxima(C, m);
  if (n == 0) return Vec2(1, 0);  // C == 0: no gradient, any direction
  const CubicHarmonics h(C);
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
  const CurvatureDerivative smoothed = CubicHarmonics::form(P, Q, R, S);
  Vec2 ms[3];
  const int ns = cubic_form_maxima(smoothed, ms);
  if (ns == 0) return m[best];
  const CubicHarmonics hs(smoothed);
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


namespace {

// The field whose zero crossings along g_p are the demarcating curves, borrowing `c` and `g`.
DirectionalFieldView demarcating_field(const Curvature& c, const CurvatureGradient& g) {
  DirectionalFieldView field;
  field.direction = g.direction.data();
  field.value = g.kappa.data();
  field.strength = g.strength.data();
  field.size = g.direction.size();
  field.axial = false;  // g_p is a vector: opposite gradients are inconsistent
  field.value_along = [&c](int v, const Vec3& t) { return c.normal_curvature(v, t); };
  field.strength_along = [&c](int v, const Vec3& t) { return std::max(0.0, c.derivative_along(v, t)); };
  return field;
}

ZeroCrossingOptions crossing_options(const DemarcatingOptions& opt) {
  ZeroCrossingOptions zo;
  zo.max_angle = opt.max_angle;
  zo.min_strength = opt.min_strength;
  return zo;
}

}  // namespace

Polylines demarcating_curves(const TriMesh& mesh, const Curvature& c, const CurvatureGradient& g,
                             const DemarcatingOptions& opt) {
  Polylines p = extract_zero_crossings(mesh, c.normal, demarcating_field(c, g), crossing_options(opt));
  return opt.min_length > 0 ? drop_short_chains(p, opt.min_length) : p;
}

CandidateCrossings demarcating_candidates(const TriMesh& mesh, const Curvature& c, const CurvatureGradient& g,
                                          const DemarcatingOptions& opt) {
  return extract_candidate_crossings(mesh, c.normal, demarcating_field(c, g), crossing_options(opt));
}

double noise_curve_strength(const NoiseEstimate& noise, double presmoothing_edges, CurvatureEstimator estimator,
                            int n) {
  if (!(noise.relative > kCleanNoise) || !std::isfinite(noise.relative) ||
      !(presmoothing_edges >= 0 && presmoothing_edges <= 100))
    return 0;
  const NoisePatch patch = make_noise_patch(noise.relative, n);
  ScaledCurvature sc = curvature_at_scale(*patch.surface, Length::in_edges(presmoothing_edges), estimator, nullptr);
  const CurvatureGradient g = curvature_gradient(*sc.curvature);
  DemarcatingOptions o;
  const Polylines all = demarcating_curves(patch.surface->mesh(), *sc.curvature, g, o);
  const int margin = noise_patch_margin(presmoothing_edges);
  const double unit = sc.scale.edge;  // patch edge -> strengths per edge length squared
  return kNoiseCurveFactor * percentile(interior_segment_strengths(all, n, margin), kNoiseCurvePercentile) * unit * unit;
}

void DemarcatingParams::validate() const {
  presmoothing.check("Pre-smoothing", 0, 100);
  require_range(relative_threshold, "Strength threshold", 0, 1000);
  require_range(min_length_edges, "Minimum curve length (edge lengths)", 0, 1e6);
  require_range(max_angle, "Direction-consistency angle (radians)", 0, kPi);
}

DemarcatingResult compute_demarcating(const TriMesh& mesh, const DemarcatingParams& p) {
  return compute_demarcating(Surface::borrow(mesh), p);
}

DemarcatingResult compute_demarcating(const Surface& surface, const DemarcatingParams& p) {
  const TriMesh& mesh = surface.mesh();
  DemarcatingResult r;
  static_cast<ScaledCurvature&>(r) = begin_curve_filter(surface, p);
  r.min_length = p.min_length_edges * r.scale.edge;
  if (p.progress) p.progress(85, "Curvature gradient");
  r.gradient = curvature_gradient(*r.curvature);
  r.median_strength = median_positive(counted_values(r.gradient.strength, r.scale.counts));
  if (p.progress) p.progress(92, "Demarcating curves");
  // The threshold is at least relative x the noise term, so segments weaker than the hysteresis'
  // share of it need not be built: only their strengths are collected, for the automatic
  // threshold's percentile.
  DemarcatingOptions o;
  o.min_strength = kLineLinking.weak_ratio * p.relative_threshold * kNoiseFactor * r.median_strength;
  o.max_angle = p.max_angle;
  CandidateCrossings candidates = demarcating_candidates(mesh, *r.curvature, r.gradient, o);
  for (double x : candidates.all_strengths) r.strongest_crossing = std::max(r.strongest_crossing, x);
  r.automatic_threshold = automatic_curve_threshold(r.median_strength, std::move(candidates.all_strengths));
  r.noise_threshold = noise_curve_strength(r.noise, r.presmoothing / r.scale.edge, p.estimator,
                                           noise_patch_cells(mesh.n_faces())) / (r.scale.edge * r.scale.edge);
  r.automatic_threshold = std::max(r.automatic_threshold, r.noise_threshold);
  r.threshold = p.relative_threshold * r.automatic_threshold;
  r.curves = select_lines(candidates.lines, r.threshold, kLineLinking, r.scale.edge, r.min_length);
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
