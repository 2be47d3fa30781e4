// ReliefKit — automatic scale selection (thesis chapter 5, after Lindeberg's γ-normalised
// derivatives): the optimal scale of a point is where t^γ f(K(t)) peaks over the scale t, f being
// the strength of the curve type (eq. 5.2). Here t is the diffusion time, the variance of the
// Gaussian the smoothing amounts to (t = σ²).
//
// The closed forms below are the thesis' 1-D results, used by the tests as known answers and by
// the filters to map a selected scale back to the feature's own width:
//  * ridges & valleys, f = |κ|, Gaussian ridge of variance t0: t_max = 2γ t0 / (3 − 2γ). The
//    thesis prints 2 t0 / (3 − 2γ) (eq. 5.11), which drops a factor γ in solving
//    γ / t = 3 / (2 (t0 + t)); the two agree at γ = 1, the value the thesis uses. The tests find
//    the peak numerically and side with 2γ t0 / (3 − 2γ) for γ = 0.75 and 1.25;
//  * relief edges, f = ∂κ/∂λ (curvature derivative across the edge, by arc length), unit-height
//    step smoothed to variance t0: t_max = (A + B) / C (eq. 5.15, Appendix A).
// Eq. 5.15 depends on the step's height and the mesh's unit (the 1 + 2π(t0 + t) terms come from
// the slope of a unit-height step), so a scan in millimetres and the same scan in metres would
// select different scales. In the small-slope limit (κ ≈ −s'', ∂κ/∂λ ≈ −s''') the smoothed
// step's strength is H / (√(2π) (t0 + t)^{3/2}) and the selected scale is 2γ t0 / (3 − 2γ), the
// ridge's: independent of the height H and of the unit. The filters use that form
// (relief_edge_optimal_scale); the thesis' is kept for comparison.
#pragma once

#include <vector>

namespace reliefkit {

/// Eq. 5.11 with its factor γ restored: 2γ t0 / (3 − 2γ) (γ < 1.5).
double ridge_optimal_scale(double t0, double gamma);
/// Eq. 5.15 for a unit-height step, in the step's own units (γ < 1.3).
double relief_edge_optimal_scale_unit_step(double t0, double gamma);
/// The scale-free form the filters use (small-slope limit, any height): 2γ t0 / (3 − 2γ).
double relief_edge_optimal_scale(double t0, double gamma);

/// The scale t at which t^γ f peaks over samples f[k * stride] at increasing scales t[k] (> 0):
/// the best sample, refined by the parabola through it and its neighbours in log t (so a
/// geometric series of scales is refined evenly). Returns 0 when no sample has a positive
/// strength; the end scales when the peak is at an end (the range did not bracket it).
double select_scale(const std::vector<double>& t, const double* f, int stride, double gamma);

/// Where a scale x lies among the levels of a scale space, given as increasing values u (log σ,
/// say): the levels `lower` and `upper` around it (adjacent; the same one when there is a single
/// level) and x's weight towards `upper`, linear in u and clamped to [0, 1], so that a scale
/// beyond the range takes the end level. `u` must not be empty.
struct ScaleBracket {
  int lower = 0, upper = 0;
  double weight = 0;
  /// (1 − weight) a + weight b: a per-level value at the scale.
  double mix(double a, double b) const { return (1 - weight) * a + weight * b; }
};
ScaleBracket bracket_scale(const std::vector<double>& u, double x);

}  // namespace reliefkit
