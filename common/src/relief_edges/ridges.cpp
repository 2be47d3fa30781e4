#include "reliefkit/relief_edges/ridges.h"
#include "reliefkit/base/curve_selection.h"
#include "reliefkit/base/smoothing.h"

#include <algorithm>
#include <cmath>

namespace reliefkit {

namespace {

// What a ridge (k1 along t1) or valley (k2 along t2) line is a zero crossing of, and its strength.
struct RidgeField {
  RidgeField() = default;
  RidgeField(const RidgeField&) = delete;  // `view` points into this object's own arrays
  RidgeField& operator=(const RidgeField&) = delete;
  std::vector<double> value, strength;
  DirectionalFieldView view;
  ZeroCrossingOptions options;
};

// `field` is filled in place: its view points into its own arrays.
void make_ridge_field(const TriMesh& mesh, const Curvature& c, bool valleys, double min_strength, RidgeField& field) {
  if (c.dcurv.size() != c.k1.size()) throw InputError("ridges and valleys need the curvature derivative tensor");
  const int nv = mesh.n_vertices();
  field.value.resize(size_t(nv)), field.strength.resize(size_t(nv));
  for (int v = 0; v < nv; ++v) {
    field.value[v] = valleys ? c.dcurv[v].d : c.dcurv[v].a;  // derivative of k2 along t2 / of k1 along t1
    field.strength[v] = valleys ? -c.k2[v] : c.k1[v];
  }
  DirectionalFieldView& f = field.view;
  f.direction = valleys ? c.dir2.data() : c.dir1.data();
  f.value = field.value.data();
  f.strength = field.strength.data();
  f.size = size_t(nv);
  f.axial = true;
  f.value_along = [&c](int v, const Vec3& t) { return c.derivative_along(v, t); };
  f.strength_along = [&c, valleys](int v, const Vec3& t) {
    double k = c.normal_curvature(v, t);
    return valleys ? -k : k;
  };
  field.options.min_strength = min_strength;
  // Keep maxima of k1 (the derivative decreases along t1) for ridges, minima of k2 for valleys:
  // the gradient of the linearly interpolated derivative across the face, against the face's
  // mean direction.
  field.options.accept_face = [&mesh, valleys](int face, const double val[3], const Vec3 dir[3]) {
    const double along = face_gradient(mesh, face, val).dot(dir[0] + dir[1] + dir[2]);
    return valleys ? along > 0 : along < 0;
  };
}

}  // namespace

Polylines ridge_lines(const TriMesh& mesh, const Curvature& c, bool valleys, double min_strength) {
  RidgeField field;
  make_ridge_field(mesh, c, valleys, min_strength, field);
  return extract_zero_crossings(mesh, c.normal, field.view, field.options);
}

CandidateCrossings ridge_candidates(const TriMesh& mesh, const Curvature& c, bool valleys, double min_strength) {
  RidgeField field;
  make_ridge_field(mesh, c, valleys, min_strength, field);
  return extract_candidate_crossings(mesh, c.normal, field.view, field.options);
}

void RidgeValleyParams::validate() const {
  presmoothing.check("Pre-smoothing", 0, 100);
  require_range(relative_threshold, "Strength threshold", 0, 1000);
  require_range(min_length_edges, "Minimum curve length (edge lengths)", 0, 1e6);
  require_range(linking.weak_ratio, "Weak line ratio", 0, 1);
  require_range(linking.gap_edges, "Bridge gaps up to", 0, 20);
}

namespace {

// The smallest threshold at which `lines` (drawn by noise alone) keep no line through the
// filter's selection (hysteresis, bridged gaps, minimum length), by bisection.
double quiet_threshold(const Polylines& lines, const RidgeValleyParams& p, double edge) {
  double lo = 0, hi = 0;
  for (double x : lines.strength) hi = std::max(hi, x);
  const double min_length = p.min_length_edges * edge;
  for (int it = 0; it < 30 && hi > 0; ++it) {
    const double mid = 0.5 * (lo + hi);
    (select_lines(lines, mid, p.linking, edge, min_length).segments.empty() ? hi : lo) = mid;
  }
  return hi;
}

}  // namespace

RidgeStrengths noise_ridge_strengths(const NoisePatch& noise_patch, double presmoothing_edges,
                                     const RidgeValleyParams& p) {
  if (!(presmoothing_edges >= 0 && presmoothing_edges <= 100)) return {};
  const Surface& patch = *noise_patch.surface;
  const int n = noise_patch.cells;
  const double edge = patch.scale().edge;
  // (the patch's own noise is not needed)
  const std::shared_ptr<const Curvature> curvature =
      smoothed_surface(patch, presmoothing_edges * edge).curvature(p.estimator, true);
  const Curvature& c = *curvature;
  const int margin = noise_patch_margin(presmoothing_edges);
  auto floor = [&](bool valleys) {
    const Polylines all = ridge_lines(patch.mesh(), c, valleys, 0.0);
    return kNoiseCurveFactor * quiet_threshold(select_segments(all, interior_segments(all, n, margin)), p, edge) * edge;
  };
  return {floor(false), floor(true)};
}

namespace {

// The noise floor of a scan (unit-free, see noise_ridge_strengths) on the given patch, or on one
// made for it; zero on a clean scan.
RidgeStrengths scan_noise_ridge_strengths(const RidgeValleyResult& r, long long faces, const RidgeValleyParams& p,
                                          const NoisePatch& given_patch) {
  if (!(r.noise.relative > kCleanNoise) || !std::isfinite(r.noise.relative)) return {};
  const double presmoothing_edges = r.presmoothing / r.scale.edge;
  const NoisePatch patch = given_patch ? given_patch : make_noise_patch(r.noise.relative, noise_patch_cells(faces));
  return noise_ridge_strengths(patch, presmoothing_edges, p);
}

}  // namespace

RidgeValleyResult compute_ridges_valleys(const TriMesh& mesh, const RidgeValleyParams& p) {
  return compute_ridges_valleys(Surface::borrow(mesh), p);
}

RidgeValleyResult compute_ridges_valleys(const Surface& surface, const RidgeValleyParams& p, const NoisePatch& noise_patch) {
  const TriMesh& mesh = surface.mesh();
  RidgeValleyResult r;
  static_cast<ScaledCurvature&>(r) = begin_curve_filter(surface, p);
  r.min_length = p.min_length_edges * r.scale.edge;
  if (p.progress) p.progress(90, "Ridges and valleys");
  std::vector<double> kmax(r.curvature->k1.size()), kmin(r.curvature->k2.size());
  for (size_t v = 0; v < kmax.size(); ++v) kmax[v] = std::abs(r.curvature->k1[v]), kmin[v] = std::abs(r.curvature->k2[v]);
  kmax = counted_values(kmax, r.scale.counts);
  kmin = counted_values(kmin, r.scale.counts);
  // Segments below relative x the noise term are never kept: only their strengths are collected.
  // Noise scale: the median curvature magnitude, but at least 1 % of the 99th percentile: on
  // exactly flat (synthetic) regions the median is ~0 and numerical wiggles of the derivative
  // would pass as ridges.
  auto noise_scale = [](std::vector<double> k) {
    double med = median_positive(k);
    if (k.empty()) return med;
    auto p99 = k.begin() + static_cast<long>(0.99 * double(k.size() - 1));
    std::nth_element(k.begin(), p99, k.end());
    return std::max(med, 0.01 * *p99);
  };
  const double noise_r = noise_scale(kmax), noise_v = noise_scale(kmin);
  const double floor = p.linking.weak_ratio * p.relative_threshold * kNoiseFactor;
  CandidateCrossings cand_r = ridge_candidates(mesh, *r.curvature, false, floor * noise_r);
  CandidateCrossings cand_v = ridge_candidates(mesh, *r.curvature, true, floor * noise_v);
  for (double x : cand_r.all_strengths) r.strongest_ridge = std::max(r.strongest_ridge, x);
  for (double x : cand_v.all_strengths) r.strongest_valley = std::max(r.strongest_valley, x);
  // At least what noise alone draws after the same pre-smoothing (on the noise patch).
  const RidgeStrengths by_noise = scan_noise_ridge_strengths(r, mesh.n_faces(), p, noise_patch);
  r.ridge_threshold = p.relative_threshold * std::max(automatic_curve_threshold(noise_r, std::move(cand_r.all_strengths)), by_noise.ridges / r.scale.edge);
  r.valley_threshold = p.relative_threshold * std::max(automatic_curve_threshold(noise_v, std::move(cand_v.all_strengths)), by_noise.valleys / r.scale.edge);
  // A line starts only where it stands out of the surface's own roughness (local_contrast).
  const double radius = contrast_radius(r.scale.edge, r.presmoothing);
  std::vector<double> minus_k2(r.curvature->k2.size());
  for (size_t v = 0; v < minus_k2.size(); ++v) minus_k2[v] = -r.curvature->k2[v];
  r.ridges = select_lines(cand_r.lines, r.ridge_threshold, p.linking, r.scale.edge, r.min_length,
                          local_contrast(surface, r.curvature->k1, radius));
  r.valleys = select_lines(cand_v.lines, r.valley_threshold, p.linking, r.scale.edge, r.min_length,
                           local_contrast(surface, minus_k2, radius));
  return r;
}

}  // namespace reliefkit
