#include "reliefkit/multiscale/multiscale.h"

#include <algorithm>
#include <cmath>

#include "reliefkit/base/curve_selection.h"
#include "reliefkit/multiscale/scale_selection.h"

namespace reliefkit {

void normalise_curve_strengths(Polylines& curves, const OptimalScale& scale, double gamma, int power) {
  const double h = scale.scale.edge;
  const int np = static_cast<int>(curves.points.size());
  const double finest = scale.levels.empty() ? 0.0 : scale.levels.front();
#pragma omp parallel for schedule(static)
  for (int i = 0; i < np; ++i) {
    const auto [a, b] = curves.point_edge[i];
    const double w = curves.point_weight[i];
    (void)w;
    // The smaller scale of the edge's two ends: where the scale changes quickly (a fine feature
    // next to smooth ground), the larger one would amplify the finer side's curvature. The scale
    // the smoothed surface holds there (smoothed_ratio x σ, at least the smallest level).
    const double s = std::max(scale.smoothed_ratio * std::min(scale.sigma[a], scale.sigma[b]), finest) / h;
    curves.strength[i] *= std::pow(s * s, gamma) * std::pow(h, power);
  }
}

void drop_banks(Polylines& curves, const OptimalScale& scale, int flanked_sign) {
  if (scale.bank_sign.empty()) return;
  auto bank = [&](int v) {
    // In a flanking feature's footprint and weaker than kBankRatio x it, or of the opposite
    // kind where it lies (a crest line drawn along a groove's floor by noise).
    return (scale.bank_sign[v] == flanked_sign && scale.own_strength[v] < kBankRatio * scale.bank_strength[v]) ||
           scale.own_sign[v] == flanked_sign;
  };
  std::vector<char> keep(curves.segments.size(), 1);
  for (size_t k = 0; k < curves.segments.size(); ++k) {
    int near_bank = 0;
    for (int p : curves.segments[k]) {
      const auto [a, b] = curves.point_edge[p];
      near_bank += bank(curves.point_weight[p] < 0.5 ? a : b);
    }
    keep[k] = near_bank < 2;
  }
  curves = select_segments(curves, keep);
}

namespace {

// The optimal scale with its smoothed surface, as the run's surface at those positions.
Surface optimally_smoothed(const Surface& surface, OptimalScaleOptions& opt, OptimalScale& out) {
  opt.smoothed_surface = true;
  out = optimal_scale(surface, opt);
  Surface smoothed = surface.with_positions(std::move(out.smoothed));
  out.smoothed.clear();
  return smoothed;
}

}  // namespace

MultiscaleRidgeValleys multiscale_ridges_valleys(const Surface& surface, OptimalScaleOptions opt,
                                                 RidgeValleyParams params) {
  params.validate();
  params.linking = kConnectingLines;
  const RidgeValleyParams finest = params;
  opt.curve = ScaleStrength::RidgesValleys;
  MultiscaleRidgeValleys r;
  const Surface smoothed_surface = optimally_smoothed(surface, opt, r.scale);
  const TriMesh& smoothed = smoothed_surface.mesh();
  params.presmoothing = Length::in_edges(0);
  RidgeValleyResult& c = r.curves;
  static_cast<ScaledCurvature&>(c) = begin_curve_filter(smoothed_surface, params);
  c.min_length = params.min_length_edges * r.scale.scale.edge;
  if (params.progress) params.progress(95, "Multi-scale ridges and valleys");
  // All crossings, their strengths normalised as in the scale selection, so that a fine and a
  // coarse feature of the same depth compare equal; the automatic threshold then sits above
  // what noise alone reaches (OptimalScale::strength_floor).
  for (bool valleys : {false, true}) {
    Polylines all = ridge_lines(smoothed, *c.curvature, valleys, 0.0);
    // The curvature across the line over the base's (on a curved object the base's own
    // curvature, times σ², would make every smooth area strong).
    std::vector<double> feature(static_cast<size_t>(smoothed.n_vertices()));
    for (int v = 0; v < smoothed.n_vertices(); ++v) {
      const Vec3& d = valleys ? c.curvature->dir2[v] : c.curvature->dir1[v];
      const double k = (valleys ? c.curvature->k2[v] : c.curvature->k1[v]) - d.dot(r.scale.base_shape[v] * d);
      feature[v] = valleys ? -k : k;
    }
    for (size_t i = 0; i < all.points.size(); ++i) {
      const auto [a, b] = all.point_edge[i];
      all.strength[i] = (1 - all.point_weight[i]) * feature[a] + all.point_weight[i] * feature[b];
    }
    normalise_curve_strengths(all, r.scale, opt.effective_gamma(), 1);
    drop_banks(all, r.scale, valleys ? 1 : -1);
    std::vector<double> seg(all.segments.size());
    for (size_t k = 0; k < seg.size(); ++k) seg[k] = 0.5 * (all.strength[all.segments[k][0]] + all.strength[all.segments[k][1]]);
    double strongest = 0;
    for (double x : seg) strongest = std::max(strongest, x);
    // The noise term of the automatic threshold is kNoiseFactor x its argument; the floor is
    // already the noise's 99th percentile.
    const double threshold =
        params.relative_threshold * automatic_curve_threshold(kCurveNoise * r.scale.strength_floor / kNoiseFactor, seg);
    // A line starts only where it stands out of the surface's own roughness (local_contrast).
    const std::vector<double> contrast =
        local_contrast(smoothed_surface, feature, kContrastRadiusEdges * r.scale.scale.edge);
    Polylines kept = select_lines(all, threshold, params.linking, r.scale.scale.edge, c.min_length, contrast);
    place_on_mesh(surface.mesh(), kept);
    (valleys ? c.valleys : c.ridges) = std::move(kept);
    (valleys ? c.valley_threshold : c.ridge_threshold) = threshold;
    (valleys ? c.strongest_valley : c.strongest_ridge) = strongest;
  }
  r.scale.smoothed = smoothed.vertices;
  add_finest_scale_lines(surface, finest, r.scale, r.curves);
  return r;
}

MultiscaleRidgeValleys multiscale_ridges_valleys(const TriMesh& mesh, OptimalScaleOptions opt,
                                                 RidgeValleyParams params) {
  return multiscale_ridges_valleys(Surface::borrow(mesh), opt, params);
}

std::vector<double> noise_tilt_at_scales(const OptimalScale& s, double final_smoothing_edges, long long faces) {
  const double h = s.scale.edge;
  const int nl = static_cast<int>(s.levels.size()), nv = static_cast<int>(s.sigma.size());
  const bool noisy = s.noise.relative > 0 && std::isfinite(s.noise.relative);  // else noise_tilt is 0
  const int cells = noise_patch_cells(faces);
  const NoisePatch patch = noisy ? s.noise_patch.carrying(s.noise.relative, cells) : NoisePatch{};
  std::vector<double> level_tilt(static_cast<size_t>(nl)), u(static_cast<size_t>(nl));
  for (int k = 0; k < nl; ++k) {
    u[k] = std::log(s.levels[k] / h);
    // The level's smoothing and the final one, as Gaussian widths add.
    const double tilt = patch ? noise_tilt(patch, std::hypot(s.levels[k] / h, final_smoothing_edges)) : 0.0;
    level_tilt[k] = std::max(tilt, 1e-12);
  }
  std::vector<double> tilt(static_cast<size_t>(nv), level_tilt.front());
#pragma omp parallel for schedule(static)
  for (int v = 0; v < nv; ++v) {
    if (!(s.sigma[v] > 0)) continue;
    const ScaleBracket b = bracket_scale(u, std::clamp(std::log(s.sigma[v] / h), u.front(), u.back()));
    tilt[v] = std::exp(b.mix(std::log(level_tilt[b.lower]), std::log(level_tilt[b.upper])));  // log-linear in log σ
  }
  return tilt;
}

void add_other_scale(Polylines& curves, const Polylines& other, double edge, double min_length) {
  std::vector<char> add = segments_near(other, curves, kSameEdgeEdges * edge);
  for (char& k : add) k = !k;
  append_curves(curves, drop_dashes(select_segments(other, add), min_length));
}

// A line blurred by the finest reading's pre-smoothing σ is flanked by lines of the other kind
// about √3 σ away (the feet of a Gaussian groove are crests), and two steps closer than σ merge
// into one bump whose edges sit about σ outside them. So the finest reading's curves within
// kFlankReach σ of the multi-scale reading's `near` (ridges: its valleys; valleys: its ridges;
// edges: its edges) are dropped: beside a feature finer than σ they are its blurred flanks, and a
// true curve there is the multi-scale reading's to draw, at its own scale. Pieces left shorter
// than `min_length` go too (they would be dashes).
void drop_blurred_flanks(Polylines& finest, const Polylines& near, double sigma, double min_length) {
  std::vector<char> keep = segments_near(finest, near, kFlankReach * sigma);
  for (char& k : keep) k = !k;
  finest = drop_dashes(select_segments(finest, keep), min_length);
}

void add_finest_scale_lines(const Surface& surface, RidgeValleyParams params, const OptimalScale& scale,
                            RidgeValleyResult& multi) {
  if (params.progress) params.progress(97, "Multi-scale ridges and valleys: the finest significant scale");
  params.progress = nullptr;
  params.presmoothing = Length::automatic();
  // The run's noise patch where it carries the scan's noise (above kCleanNoise a floor is measured).
  const double noise = surface.noise().relative;
  const NoisePatch patch = noise > kCleanNoise && std::isfinite(noise)
                               ? scale.noise_patch.carrying(noise, noise_patch_cells(surface.mesh().n_faces()))
                               : NoisePatch{};
  const RidgeValleyResult finest = compute_ridges_valleys(surface, params, patch);
  const double h = surface.scale().edge;
  // The finest lines' strengths as the multi-scale ones' ((σ / h)² |k| h, γ = 1), σ their
  // pre-smoothing, at least the smallest scale of the range.
  const double sigma = std::max(finest.presmoothing, scale.levels.front()) / h;
  // Both kinds' flanks are judged against the multi-scale lines before either is joined to them.
  Polylines lines[2] = {finest.ridges, finest.valleys};
  for (int valleys : {0, 1}) {
    for (double& x : lines[valleys].strength) x *= sigma * sigma * h;
    drop_blurred_flanks(lines[valleys], valleys ? multi.ridges : multi.valleys, finest.presmoothing, multi.min_length);
  }
  for (int valleys : {0, 1}) {
    Polylines& wider = valleys ? multi.valleys : multi.ridges;
    add_other_scale(lines[valleys], wider, h, multi.min_length);
    wider = std::move(lines[valleys]);
  }
}

void add_finest_scale_edges(const Surface& surface, ReliefEdgeParams params, const OptimalScale& scale,
                            ReliefEdgeResult& multi) {
  if (params.progress) params.progress(97, "Multi-scale relief edges: the finest significant scale");
  params.progress = nullptr;
  params.presmoothing = Length::automatic();
  // The scan's noise tilt measured on the run's noise patch (when it carries the scan's noise).
  ReliefEdgeGuidance guidance;
  const double noise = surface.noise().relative;
  if (noise > 0 && std::isfinite(noise))
    guidance.noise_patch = scale.noise_patch.carrying(noise, noise_patch_cells(surface.mesh().n_faces()));
  const ReliefEdgeResult finest = compute_relief_edges(surface, params, guidance);
  Polylines edges = finest.edges;
  drop_blurred_flanks(edges, multi.edges, finest.presmoothing, multi.min_length);
  add_other_scale(multi.edges, edges, scale.scale.edge, multi.min_length);
}

MultiscaleReliefEdges multiscale_relief_edges(const Surface& surface, OptimalScaleOptions opt,
                                              ReliefEdgeParams params) {
  params.validate();
  opt.curve = ScaleStrength::ReliefEdges;
  const TriMesh& mesh = surface.mesh();
  MultiscaleReliefEdges r;
  // The detector reads its lengths (minimum length, gap, edge smoothing) in the smoothed surface's
  // own median edge, as it always has: that surface gets its own scale and noise (the run's
  // adjacency). The scan's edge, the unit the parameters name, is not yet used: it moved the
  // bunny's edges by 1.6 % of their length (docs/multiscale.md).
  const Surface smoothed(optimally_smoothed(surface, opt, r.scale).mesh(), surface.topology().faces);
  // The detector on the smoothed surface, without pre-smoothing of its own, told what varies with
  // the scale (each measured on the test relief, docs/multiscale.md):
  // - the base: the surface at kReliefBaseFactor x the largest scale — its normals for the tilt, its
  //   shape operator for G (on a curved object a wide step's G crossed zero off its centre);
  // - the noise: the tilt noise leaves at each vertex's own scale (one threshold for all let the
  //   fine scales' noise through or cut the coarse scales' soft steps);
  // - the fit-error radius: kFitRadiusWidths x the vertex's scale (a soft step read at 10 edge
  //   lengths does not fit within the fine features' 4);
  // - only crossings where the slope is steepest (a soft footprint's flat wiggles crossed too).
  const ReliefEdgeParams finest = params;
  params.presmoothing = Length::in_edges(0);
  ReliefEdgeGuidance guidance;
  guidance.base_normals = r.scale.base_normal;
  guidance.base_shape = r.scale.base_shape;
  guidance.noise_tilt = noise_tilt_at_scales(r.scale, opt.final_smoothing_edges, mesh.n_faces());
  guidance.feature_width = r.scale.sigma;
  guidance.steepest_only = true;
  guidance.tilt_across = true;
  r.curves = compute_relief_edges(smoothed, params, guidance);
  r.noise_angle = r.curves.noise_angle;
  place_on_mesh(mesh, r.curves.edges);
  r.scale.smoothed = smoothed.mesh().vertices;
  add_finest_scale_edges(surface, finest, r.scale, r.curves);
  return r;
}

MultiscaleReliefEdges multiscale_relief_edges(const TriMesh& mesh, OptimalScaleOptions opt, ReliefEdgeParams params) {
  return multiscale_relief_edges(Surface::borrow(mesh), opt, params);
}

}  // namespace reliefkit
