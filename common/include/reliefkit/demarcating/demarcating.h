// ReliefKit — demarcating curves (thesis chapter 3; Kolomenkin, Shimshoni, Tal, "On edge
// detection on surfaces", CVPR 2009 / "Demarcating curves for shape illustration", SIGGRAPH
// Asia 2008) and mean-curvature shading for illustration (thesis section 3.6).
//
// Demarcating curves are the loci where the normal curvature in the curvature-gradient
// direction g_p changes sign: k(g_p) = g_p^T II g_p = 0 (Definition 3.3.2), where g_p is the
// unit tangent direction maximising C(v,v,v), the derivative of the normal curvature along v
// (Definition 3.3.1, eq. 3.2). Their strength is C(g_p, g_p, g_p) > 0: the rate of the
// convex-to-concave transition across the curve, in 1/length^2.
#pragma once

#include "reliefkit/base/curvature.h"
#include "reliefkit/base/curve_selection.h"
#include "reliefkit/base/zero_crossings.h"

namespace reliefkit {

/// Per-vertex curvature gradient.
struct CurvatureGradient {
  std::vector<Vec3> direction;   // #V unit tangent g_p (a vector: its sign matters)
  std::vector<double> kappa;     // #V k(g_p), 1/length
  std::vector<double> strength;  // #V C(g_p, g_p, g_p) >= 0, 1/length^2
  long long competing = 0;       // vertices with three maxima, resolved by the Gaussian rule
};

/// Gaussian width (radians) with which the angular function C(v(theta)) is smoothed when it has
/// three maxima (thesis 3.3.2 leaves it open): pi / 8 halves the third harmonic and keeps 93 % of
/// the first, so the maximum that agrees with the overall slope of the curvature wins.
constexpr double kCompetingMaximaSigma = 0.39269908169872414;

/// Angle theta of g_p in the principal frame, g_p = cos(theta) dir1 + sin(theta) dir2, by the
/// closed form of eqs. 3.3-3.6 (a cubic in sin^2 theta). With three real roots, the three
/// maxima compete: the function is smoothed with a Gaussian of width `sigma` (a trigonometric
/// polynomial again, whose maxima come from the same closed form) and the maximum of C nearest
/// to the smoothed function's global maximum is returned. `competing` (optional) tells which.
double curvature_gradient_angle(const CurvatureDerivative& C, double sigma = kCompetingMaximaSigma,
                                bool* competing = nullptr);
/// The same as the unit vector (cos theta, sin theta), computed without trigonometric calls.
Vec2 curvature_gradient_direction(const CurvatureDerivative& C, double sigma = kCompetingMaximaSigma,
                                  bool* competing = nullptr);

/// g_p, k(g_p) and strength at every vertex (in parallel).
CurvatureGradient curvature_gradient(const Curvature& curvature);


struct DemarcatingOptions {
  double min_strength = 0;              // absolute strength threshold (1/length^2)
  double max_angle = 0.78539816339744831;  // direction-consistency angle (pi/4, thesis 3.3.2)
  double min_length = 0;                // drop curves shorter than this (mesh units)
};

/// The demarcating curves: zero crossings of k(g_p) along g_p (shared extraction, with the
/// direction-consistency rule and sub-edge interpolation), point strength C(g_p, g_p, g_p).
Polylines demarcating_curves(const TriMesh& mesh, const Curvature& curvature, const CurvatureGradient& gradient,
                             const DemarcatingOptions& options);
/// The crossings at options.min_strength and above (min_length not applied) with the strengths of
/// all crossing segments, for the automatic threshold (CandidateCrossings).
CandidateCrossings demarcating_candidates(const TriMesh& mesh, const Curvature& curvature,
                                          const CurvatureGradient& gradient, const DemarcatingOptions& options);

/// The whole method with the defaults users get from the filter. Lengths are multiples of the
/// scan's typical edge length (MeshScale::edge), so the same parameters suit any unit.
/// The automatic strength threshold is reliefkit::automatic_curve_threshold() (curve_selection.h)
/// with the median vertex strength (over the vertices that count, MeshScale) as noise scale.
struct DemarcatingParams {
  static constexpr double kDefaultRelativeThreshold = 1.0;  // x automatic threshold
  static constexpr double kDefaultMinLengthEdges = kDashEdges;  // x edge length
  CurvatureEstimator estimator = CurvatureEstimator::Jet;
  Length presmoothing = Length::automatic();  // automatic: from the noise level
  double relative_threshold = kDefaultRelativeThreshold;
  double min_length_edges = kDefaultMinLengthEdges;
  double max_angle = 0.78539816339744831;
  Progress progress = nullptr;
  /// Throws InputError naming the first parameter out of its range.
  void validate() const;
};

/// The first stage's results (scale, noise, pre-smoothing used, curvature) and the curves.
struct DemarcatingResult : ScaledCurvature {
  CurvatureGradient gradient;
  Polylines curves;
  double median_strength = 0;    // of the vertices that count, 1/length^2
  double automatic_threshold = 0;  // automatic_curve_threshold(median strength, all crossings)
  double noise_threshold = 0;    // what noise alone draws (noise_curve_strength), 1/length^2
  double threshold = 0;          // absolute strength threshold used = relative x automatic
  double strongest_crossing = 0; // the strongest zero crossing seen (to explain an empty result)
  double min_length = 0;         // used, mesh units
};

/// The strength that demarcating curves drawn by noise alone reach (kNoiseCurvePercentile of the
/// crossings on noise_patch at the same pre-smoothing, x kNoiseCurveFactor), in units of
/// 1/(edge length)^2; 0 on a clean mesh. The automatic threshold is at least this.
double noise_curve_strength(const NoiseEstimate& noise, double presmoothing_edges, CurvatureEstimator estimator,
                            int patch_cells = 100);

/// Curvature (with pre-smoothing), curvature gradient, curves above the threshold.
/// Throws InputError for meshes require_triangles rejects.
DemarcatingResult compute_demarcating(const Surface& surface, const DemarcatingParams& params = {});
DemarcatingResult compute_demarcating(const TriMesh& mesh, const DemarcatingParams& params = {});

/// Mean-curvature shading for illustration (thesis 3.6, fig. 3.11 e): grey level
///   0.5 + atan(contrast * H / H_ref) / pi   in (0, 1),
/// light on convex parts, dark on concave ones. H_ref is the 90th percentile of |H| over the
/// vertices: the curvature of the mesh's most curved tenth (its relief) maps to a quarter of the
/// grey range on either side of mid-grey at contrast 1, whatever the scale. (The median was tried
/// first: on a clean surface it is near zero and flat parts came out grey-white.)
std::vector<double> mean_curvature_shading(const Curvature& curvature, double contrast);

/// Multiplies by (1 - amount) the grey level of the vertices of the faces the curves cross.
void darken_along_curves(const TriMesh& mesh, const Polylines& curves, double amount, std::vector<double>& grey);

}  // namespace reliefkit
