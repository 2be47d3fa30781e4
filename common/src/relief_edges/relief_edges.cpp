#include "reliefkit/base/angles.h"
#include "reliefkit/relief_edges/relief_edges.h"
#include "reliefkit/base/curve_selection.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>

#include "reliefkit/base/cubic_form.h"
#include "reliefkit/base/memory.h"
#include "reliefkit/base/smoothing.h"

namespace reliefkit {
namespace {
constexpr double kA = 5 * kPi / 8, kB = kPi / 8;  // eq. 4.19
const double kCosMaxTurn = std::cos(kPi / 4);

// The edge direction maximising the correlation inside the window |theta - base| <= w
// (eqs. 4.15-4.17): the maxima inside the window and the window's ends are the candidates.
Vec2 restricted_direction(const CubicHarmonics& h, const Vec2* maxima, int n, const Vec2& base, double cos_w,
                          double sin_w) {
  Vec2 best(0, 0);
  double best_f = -1e300;
  auto take = [&](const Vec2& v) {
    double f = h.f(v.x(), v.y());
    if (f > best_f) best_f = f, best = v;
  };
  for (int i = 0; i < n; ++i)
    if (maxima[i].dot(base) >= cos_w) take(maxima[i]);
  take(Vec2(base.x() * cos_w - base.y() * sin_w, base.y() * cos_w + base.x() * sin_w));
  take(Vec2(base.x() * cos_w + base.y() * sin_w, base.y() * cos_w - base.x() * sin_w));
  return best;
}

}  // namespace

CurvatureDerivative edge_correlation_form(const CurvatureDerivative& C) {
  return {C.a * kA + 3 * C.c * kB, (3 * C.b + C.d) * kB, (3 * C.c + C.a) * kB, C.d * kA + 3 * C.b * kB};
}

double edge_fit_error(const CurvatureDerivative& C, double k1, double k2, double f, double radius) {
  const double a1 = C.a, a2 = C.b, a3 = C.c, a4 = C.d;
  const double s1 = kA * (a1 * a1 + a4 * a4) + 9 * kB * (a2 * a2 + a3 * a3) + 6 * kB * (a1 * a3 + a2 * a4);
  const double s2 = 0.75 * kPi * (k1 * k1 + k2 * k2) + 0.5 * kPi * k1 * k2;
  const double norm = s1 + 12 * s2 / (radius * radius);
  if (!(norm > 0)) return 1;
  return std::clamp(1 - f * f / kA / norm, 0.0, 1.0);
}

double noise_tilt(const NoiseEstimate& noise, double presmoothing_edges, int n) {
  if (!(noise.relative > 0) || !std::isfinite(noise.relative) || !(presmoothing_edges >= 0 && presmoothing_edges <= 100))
    return 0;
  return noise_tilt(make_noise_patch(noise.relative, n), presmoothing_edges);
}

double noise_tilt(const NoisePatch& patch, double presmoothing_edges) {
  if (!(presmoothing_edges >= 0 && presmoothing_edges <= 100)) return 0;
  const Surface& surface = *patch.surface;
  const ScaledCurvature sc =
      curvature_at_scale(surface, Length::in_edges(presmoothing_edges), CurvatureEstimator::Jet, nullptr);
  const int margin = noise_patch_margin(presmoothing_edges);
  std::vector<double> tilt;
  for (int v = 0; v < surface.n_vertices(); ++v) {
    if (!inside_noise_patch(v, patch.cells, margin)) continue;
    tilt.push_back(std::acos(std::clamp(sc.curvature->normal[v].z(), -1.0, 1.0)));
  }
  return kNoiseTiltFactor * percentile(tilt, kNoiseCurvePercentile);
}

void ReliefEdgeParams::validate() const {
  presmoothing.check("Pre-smoothing", 0, 100);
  base_scale.check("Base surface scale", 0.5, 10000);
  edge_smoothing.check("Edge smoothing", 0, 100);
  require_range(min_length_edges, "Minimum curve length (edge lengths)", 0, 1e6);
  require_range(link_gap_edges, "Gap bridging (edge lengths)", 0, 20);
  require_range(fit_radius_edges, "Fit radius (edge lengths)", 0.5, 100);
  require_range(strong_error, "Model error, strong edges", 0, 1);
  require_range(weak_error, "Model error, weak edges", 0, 1);
  require_range(strong_angle, "Steepness, strong edges", 0, kPi / 2);
  require_range(weak_angle, "Steepness, weak edges", 0, kPi / 2);
  require_range(restriction_min_tilt, "Orientation restriction angle", 0, kPi / 2);
}

namespace {

// Step 1: the lengths the run uses, in mesh units; the fit radius and base scale follow the
// features' own width.
void resolve_lengths(const TriMesh& mesh, const ReliefEdgeParams& p, ReliefEdgeFields& r) {
  const double h = r.scale.edge;
  p.base_scale.check("Base surface scale", 0.5, 10000, h);
  p.edge_smoothing.check("Edge smoothing", 0, 100, h);
  r.feature_width = feature_width(mesh, *r.curvature, r.scale, r.topology.get());
  r.base_scale = p.base_scale.resolve(h, std::max(automatic_base_scale(r.scale), kBaseScaleWidths * r.feature_width));
  r.edge_smoothing = p.edge_smoothing.resolve(h, ReliefEdgeParams::kDefaultEdgeSmoothingEdges * h);
  r.fit_radius = std::max(p.fit_radius_edges * h, kFitRadiusWidths * r.feature_width);
}

// Step 3: per vertex the unrestricted best edge direction, the base direction (up the relief's
// slope, in the principal frame) and whether the latter is meaningful; and the orientation window.
struct EdgeFrames {
  std::vector<Vec2> best, base;
  std::vector<char> strong_base;
};
EdgeFrames edge_frames(const ReliefEdgeParams& p, ReliefEdgeFields& r) {
  const Curvature& c = *r.curvature;
  const int nv = static_cast<int>(c.k1.size());
  EdgeFrames e;
  e.best.resize(nv), e.base.resize(nv), e.strong_base.assign(nv, 0);
  sized(r.angle, size_t(nv));
#pragma omp parallel for schedule(static)
  for (int v = 0; v < nv; ++v) {
    const Vec3& n = c.normal[v];
    const Vec3& nb = r.base.normal[v];
    r.angle[v] = std::acos(std::clamp(n.dot(nb), -1.0, 1.0));
    Vec3 proj = nb - n * n.dot(nb);  // points up the relief's slope
    Vec2 b(proj.dot(c.dir1[v]), proj.dot(c.dir2[v]));
    double bl = b.norm();
    e.base[v] = bl > 0 ? Vec2(b / bl) : Vec2(1, 0);
    e.strong_base[v] = r.angle[v] > p.restriction_min_tilt && bl > 0;
    Vec2 m[3];
    int k = cubic_form_maxima(edge_correlation_form(c.dcurv[v]), m);
    if (k == 0) {
      e.best[v] = e.base[v];
      continue;
    }
    CubicHarmonics hh(edge_correlation_form(c.dcurv[v]));
    int bi = 0;
    for (int i = 1; i < k; ++i)
      if (hh.f(m[i].x(), m[i].y()) > hh.f(m[bi].x(), m[bi].y())) bi = i;
    e.best[v] = m[bi];
  }
  // Window w: the RMS angle between the unrestricted direction and the base direction, over the
  // vertices where the base direction is meaningful (thesis: the standard deviation of that
  // error's histogram).
  double sum2 = 0;
  long cnt = 0;
  for (int v = 0; v < nv; ++v)
    if (e.strong_base[v] && (r.scale.counts.empty() || r.scale.counts[v])) {  // debris does not count
      double d = std::acos(std::clamp(e.best[v].dot(e.base[v]), -1.0, 1.0));
      sum2 += d * d;
      ++cnt;
    }
  r.window = std::clamp(cnt > 0 ? std::sqrt(sum2 / cnt) : kPi, 10 * kPi / 180, kPi);
  return e;
}

// The given base's normal curvature along g (principal frame of v); 0 without a given base.
double base_curvature(const ReliefEdgeGuidance& guide, const Curvature& c, int v, const Vec2& g) {
  if (guide.base_shape.empty()) return 0;
  const Vec3 t = g.x() * c.dir1[v] + g.y() * c.dir2[v];
  return t.dot(guide.base_shape[v] * t);
}

// Step 4: the edge direction g (restricted to the window around the base direction), the edge
// intensity, the model's fit error and G = g^T II g. Returns g in the principal frame.
std::vector<Vec2> edge_model(const ReliefEdgeParams& p, const ReliefEdgeGuidance& guide, const EdgeFrames& e,
                             ReliefEdgeFields& r) {
  const Curvature& c = *r.curvature;
  const int nv = static_cast<int>(c.k1.size());
  const double cos_w = std::cos(r.window), sin_w = std::sin(r.window);
  sized(r.G, size_t(nv));
  sized(r.alpha, size_t(nv));
  sized(r.fit_error, size_t(nv));
  std::vector<Vec2> g2(nv);
#pragma omp parallel for schedule(static)
  for (int v = 0; v < nv; ++v) {
    const CurvatureDerivative form = edge_correlation_form(c.dcurv[v]);
    const CubicHarmonics hh(form);
    Vec2 g = e.best[v];
    if (p.restrict_orientation && e.strong_base[v] && r.window < kPi) {
      Vec2 m[3];
      int k = cubic_form_maxima(form, m);
      g = restricted_direction(hh, m, k, e.base[v], cos_w, sin_w);
    }
    const double f = hh.f(g.x(), g.y());
    r.alpha[v] = f / kA;
    const double radius = guide.feature_width.empty()
                              ? r.fit_radius
                              : std::max(r.fit_radius, kFitRadiusWidths * guide.feature_width[v]);
    r.fit_error[v] = edge_fit_error(c.dcurv[v], c.k1[v], c.k2[v], f, radius);
    g2[v] = g;
    r.G[v] = c.k1[v] * g.x() * g.x() + c.k2[v] * g.y() * g.y() - base_curvature(guide, c, v, g);
  }
  return g2;
}

// Step 5, edge smoothing (eq. 4.18): smooth G, then recover directions giving the smoothed value,
// nearest to the current ones; where none exists, the nearest value.
void smooth_edges(const Surface& surface, const ReliefEdgeGuidance& guide, std::vector<Vec2>& g2, ReliefEdgeFields& r) {
  const Curvature& c = *r.curvature;
  const int nv = static_cast<int>(c.k1.size());
  std::vector<double> Gs = r.G;
  diffuse(surface, r.edge_smoothing, Gs);
#pragma omp parallel for schedule(static)
  for (int v = 0; v < nv; ++v) {
    const double k1 = c.k1[v], k2 = c.k2[v];
    Vec2 g = g2[v];
    // With a given base, G is over the base's curvature along the current g (which changes
    // little in the step below).
    const double b = base_curvature(guide, c, v, g), target = Gs[v] + b;
    if (k1 - k2 > 1e-12 * (std::abs(k1) + std::abs(k2))) {
      double c2 = std::clamp((target - k2) / (k1 - k2), 0.0, 1.0);
      double cs = std::sqrt(c2), sn = std::sqrt(1 - c2);
      Vec2 cand(std::copysign(cs, g.x()), std::copysign(sn, g.y()));  // the candidate nearest g
      // Where the smoothed value is out of reach the nearest direction is a principal one,
      // which can be far from g; a turn of more than the consistency angle would break the
      // curve there, so such vertices keep their direction.
      if (cand.dot(g) >= kCosMaxTurn || (target >= k2 && target <= k1)) {
        g = cand;
        r.G[v] = k1 * c2 + k2 * (1 - c2) - b;
      }
    }
    g2[v] = g;
  }
}

// The noise tilt at each crossing point (the guidance's, interpolated); empty without it.
std::vector<double> crossing_noise(const Polylines& all, const ReliefEdgeGuidance& guide) {
  return guide.noise_tilt.empty() ? std::vector<double>() : interpolate_at_points(all, guide.noise_tilt);
}

// The least tilt noise gives: the smallest of the guidance's per-vertex tilts (reported; each
// point has its own), else that of the estimated noise after the run's pre-smoothing.
double least_noise_tilt(const TriMesh& mesh, const ReliefEdgeFields& r, const ReliefEdgeGuidance& guide) {
  if (guide.noise_tilt.empty() && guide.noise_patch && r.noise.relative > 0 && std::isfinite(r.noise.relative))
    return noise_tilt(guide.noise_patch, r.presmoothing / r.scale.edge);
  if (guide.noise_tilt.empty())
    return noise_tilt(r.noise, r.presmoothing / r.scale.edge, noise_patch_cells(mesh.n_faces()));
  double least = 0;
  bool first = true;
  for (double x : guide.noise_tilt)
    if (std::isfinite(x) && (first || x < least)) least = x, first = false;
  return least;
}

// Step 6: the hysteresis thresholds on the tilt. Automatic from the crossings (the same rule as
// for demarcating curves; angles are scale-free), and above the tilt that the estimated noise
// alone gives after the same pre-smoothing (noise_tilt). The thesis' fixed 11 degrees (used
// before) kept 10 % noise out at one edge length of smoothing but lost the coin's lettering, which
// tilts by 4-10 degrees; the weak threshold is half the strong one.
// The crossings' percentile is taken over those above the noise's tilt: on a finely meshed noisy
// scan the noise's crossings outnumber the relief's and pulled the percentile (and with it the
// threshold, to 1.2 degrees at 1 M faces) down to where the feet and tops of the steps passed as
// edges.
ReliefEdgeThresholds tilt_thresholds(const TriMesh& mesh, const ReliefEdgeParams& p, const ReliefEdgeFields& r,
                                     const Polylines& all, const std::vector<double>& point_noise,
                                     const ReliefEdgeGuidance& guide) {
  ReliefEdgeThresholds t;
  t.noise_angle = least_noise_tilt(mesh, r, guide);
  std::vector<double> above_noise;
  for (const auto& sg : all.segments) {
    const double a = 0.5 * (all.strength[sg[0]] + all.strength[sg[1]]);
    const double nz = point_noise.empty() ? t.noise_angle : 0.5 * (point_noise[sg[0]] + point_noise[sg[1]]);
    t.steepest_crossing = std::max(t.steepest_crossing, a);
    if (a > nz) above_noise.push_back(a);
  }
  t.automatic_angle =
      automatic_curve_threshold(median_positive(counted_values(r.angle, r.scale.counts)), std::move(above_noise));
  t.strong_angle = p.strong_angle > 0 ? p.strong_angle
                   : point_noise.empty() ? std::max(t.automatic_angle, t.noise_angle)
                                         : t.automatic_angle;
  t.weak_angle = p.weak_angle > 0 ? p.weak_angle : 0.5 * t.strong_angle;
  return t;
}

// Step 7: two-dimensional hysteresis (fit error and tilt), then the gaps it leaves are bridged —
// pieces whose ends face each other across a small gap are joined (on the coin the share of curve
// length in pieces under 10 edge lengths fell from 0.60) — and short fragments dropped.
void select_edges(const ReliefEdgeParams& p, const Polylines& all, const std::vector<double>& point_noise,
                  ReliefEdgeResult& r) {
  const std::vector<double> err = interpolate_at_points(all, r.fit_error);
  const size_t ns = all.segments.size();
  std::vector<char> strong(ns), weak(ns);
  for (size_t k = 0; k < ns; ++k) {
    const auto& s = all.segments[k];
    double e = 0.5 * (err[s[0]] + err[s[1]]), a = 0.5 * (all.strength[s[0]] + all.strength[s[1]]);
    const double nz = point_noise.empty() || p.strong_angle > 0 ? 0.0 : 0.5 * (point_noise[s[0]] + point_noise[s[1]]);
    strong[k] = e <= p.strong_error && a >= std::max(r.strong_angle, nz);
    weak[k] = e <= p.weak_error && a >= std::max(r.weak_angle, 0.5 * nz);
  }
  r.edges = connect_lines(all, strong, weak, p.link_gap_edges * r.scale.edge, r.min_length, &r.links);
}

// Per-vertex guidance must have one value per vertex (or none).
void check_guidance(const ReliefEdgeGuidance& guide, size_t nv) {
  auto wrong_size = [nv](const auto& x) { return !x.empty() && x.size() != nv; };
  if (wrong_size(guide.base_normals) || wrong_size(guide.base_shape) || wrong_size(guide.noise_tilt) ||
      wrong_size(guide.feature_width))
    throw std::invalid_argument("relief edges: a per-vertex guidance input has another vertex count than the mesh");
}

// The tilt across the edge at every vertex: asin of the base normal's tangential part along g.
std::vector<double> tilt_across_edges(const ReliefEdgeFields& r) {
  const Curvature& c = *r.curvature;
  const int nv = static_cast<int>(c.k1.size());
  std::vector<double> across;
  sized(across, size_t(nv));
#pragma omp parallel for schedule(static)
  for (int v = 0; v < nv; ++v) {
    const Vec3& n = c.normal[v];
    const Vec3& nb = r.base.normal[v];
    const double s = std::abs((nb - n * n.dot(nb)).dot(r.direction[v]));
    across[v] = std::asin(std::clamp(s, 0.0, 1.0));
  }
  return across;
}

}  // namespace

ReliefEdgeFields compute_relief_edge_fields(const Surface& surface, const ReliefEdgeParams& p,
                                            const ReliefEdgeGuidance& guide) {
  const TriMesh& mesh = surface.mesh();
  ReliefEdgeFields r;
  // Step 1: scale, noise, pre-smoothing and curvature with derivatives (shared first stage).
  static_cast<ScaledCurvature&>(r) = begin_curve_filter(surface, p);
  resolve_lengths(mesh, p, r);
  const Curvature& c = *r.curvature;

  // Step 2: the base surface's normals.
  if (p.progress) p.progress(60, "Base normals");
  check_guidance(guide, c.normal.size());
  if (!guide.base_normals.empty()) {
    r.base.normal = guide.base_normals;
  } else {
    BaseNormalOptions bo;
    bo.scale = r.base_scale;
    r.base = estimate_base_normals(surface, c.normal, bo);
  }

  // Steps 3-5: edge directions, the edge model, edge smoothing.
  if (p.progress) p.progress(80, "Edge directions");
  const EdgeFrames frames = edge_frames(p, r);
  std::vector<Vec2> g2 = edge_model(p, guide, frames, r);
  if (r.edge_smoothing > 0) {
    if (p.progress) p.progress(88, "Edge smoothing");
    smooth_edges(surface, guide, g2, r);
  }
  sized(r.direction, c.k1.size(), Vec3(Vec3::Zero()));
#pragma omp parallel for schedule(static)
  for (int v = 0; v < mesh.n_vertices(); ++v) r.direction[v] = g2[v].x() * c.dir1[v] + g2[v].y() * c.dir2[v];
  return r;
}

Polylines relief_edge_crossings(const Surface& surface, const ReliefEdgeFields& r, const ReliefEdgeGuidance& guide) {
  const TriMesh& mesh = surface.mesh();
  const Curvature& c = *r.curvature;
  if (r.G.size() != size_t(mesh.n_vertices()))
    throw std::invalid_argument("relief_edge_crossings: the fields have another vertex count than the mesh");
  check_guidance(guide, r.G.size());
  DirectionalFieldView f;
  f.direction = r.direction.data();
  f.value = r.G.data();
  const std::vector<double> across = guide.tilt_across ? tilt_across_edges(r) : std::vector<double>();
  f.strength = guide.tilt_across ? across.data() : r.angle.data();
  f.size = c.k1.size();
  f.axial = false;
  f.value_along = [&c, &guide](int v, const Vec3& t) {
    const Vec2 u(t.dot(c.dir1[v]), t.dot(c.dir2[v]));  // in v's principal frame, unit
    const double n = u.norm();
    return n > 0 ? c.normal_curvature(v, t) - base_curvature(guide, c, v, u / n) : 0.0;
  };
  ZeroCrossingOptions zo;
  if (guide.steepest_only)  // G < 0 at a step's foot, > 0 at its top: it rises along g (up the slope)
    zo.accept_face = [&mesh](int face, const double val[3], const Vec3 dir[3]) {
      return face_gradient(mesh, face, val).dot(dir[0] + dir[1] + dir[2]) > 0;
    };
  return extract_zero_crossings(mesh, c.normal, f, zo);
}

ReliefEdgeThresholds relief_edge_thresholds(const Surface& surface, const ReliefEdgeFields& fields,
                                            const Polylines& crossings, const ReliefEdgeParams& params,
                                            const ReliefEdgeGuidance& guidance) {
  return tilt_thresholds(surface.mesh(), params, fields, crossings, crossing_noise(crossings, guidance), guidance);
}

ReliefEdgeResult compute_relief_edges(const TriMesh& mesh, const ReliefEdgeParams& p, const ReliefEdgeGuidance& guide) {
  return compute_relief_edges(Surface::borrow(mesh), p, guide);
}

ReliefEdgeResult compute_relief_edges(const Surface& surface, const ReliefEdgeParams& p,
                                      const ReliefEdgeGuidance& guide) {
  ReliefEdgeResult r;
  static_cast<ReliefEdgeFields&>(r) = compute_relief_edge_fields(surface, p, guide);
  // Relief edge points: zeros of G along g; strength = angle between surface and base normal.
  if (p.progress) p.progress(93, "Relief edge points");
  const Polylines all = relief_edge_crossings(surface, r, guide);
  const std::vector<double> point_noise = crossing_noise(all, guide);
  static_cast<ReliefEdgeThresholds&>(r) = tilt_thresholds(surface.mesh(), p, r, all, point_noise, guide);
  r.min_length = p.min_length_edges * r.scale.edge;
  select_edges(p, all, point_noise, r);
  return r;
}

}  // namespace reliefkit
