// ReliefKit — relief edges (thesis chapter 4; Kolomenkin, Shimshoni, Tal, "On edge detection on
// surfaces", CVPR 2009).
//
// A scanned relief is a smooth base B carrying a local image I along the base normal (eq. 4.1);
// relief edges are the edges of that image. At every vertex a smoothed step edge
// E = alpha/6 (c u + s v)^3 is fitted to the local Monge form; its direction maximises the
// correlation <E1(theta), S1> = c^3 C1 + 3c^2 s C2 + 3c s^2 C3 + s^3 C4 (eq. 4.13, Appendix A),
// alpha = <E1, S1> / ||E1||^2 (eq. 4.14). The orientation is restricted to a window around the
// direction the base normal gives (eqs. 4.15-4.17); G = g^T II g (g perpendicular to the edge)
// is Gaussian-smoothed and directions are recovered from it (eq. 4.18); relief edge points are
// the zeros of G (Definition 4.3.1), kept by a two-dimensional hysteresis on the model-fit error
// (eq. 4.7 normalised by ||S||^2) and the edge strength, the angle between surface and base
// normal (1 / (n . n_base) grows with it).
#pragma once

#include "reliefkit/relief_edges/base_normals.h"
#include "reliefkit/base/curvature.h"
#include "reliefkit/base/curve_selection.h"
#include "reliefkit/base/noise_patch.h"
#include "reliefkit/base/zero_crossings.h"

namespace reliefkit {

/// C1..C4 of eq. 4.13 from the derivative tensor (a1..a4) = (a, b, c, d), with A = 5 pi / 8 and
/// B = pi / 8 (eq. 4.19): C1 = a1 A + 3 a3 B, C2 = (3 a2 + a4) B, C3 = (3 a3 + a1) B,
/// C4 = a4 A + 3 a2 B. Returned as a cubic form, so cubic_form_maxima() finds its maxima.
CurvatureDerivative edge_correlation_form(const CurvatureDerivative& C);

/// Fit error of eq. 4.7 at the optimum, normalised by ||S||^2, for correlation f = <E1, S1>:
///   1 - (f^2 / A) / (||S1||^2 + 12 ||S2||^2 / R^2),
/// where S1 is the cubic and S2 the quadratic part of the Monge form and R the radius of the
/// neighbourhood the error is integrated over (the radial integrals give the 12 / R^2). In [0, 1]:
/// 0 for a perfect step edge.
double edge_fit_error(const CurvatureDerivative& C, double k1, double k2, double f, double radius);

struct ReliefEdgeParams {  // what the user chooses
  static constexpr double kDefaultEdgeSmoothingEdges = 0.8;  // x edge length (thesis 4.4)
  static constexpr double kDefaultMinLengthEdges = kDashEdges;  // x edge length
  static constexpr double kDefaultFitRadiusEdges = 4.0;      // x edge length (see relief_edges.md)
  static constexpr double kDefaultLinkGapEdges = 3.0;        // x edge length
  CurvatureEstimator estimator = CurvatureEstimator::Jet;
  // Lengths, in multiples of the typical edge length (MeshScale::edge).
  Length presmoothing = Length::automatic();    // automatic: from the noise level
  Length base_scale = Length::automatic();      // automatic: kDefaultBaseScaleEdges
  Length edge_smoothing = Length::automatic();  // automatic: kDefaultEdgeSmoothingEdges
  double min_length_edges = kDefaultMinLengthEdges;
  double link_gap_edges = kDefaultLinkGapEdges;  // join curve ends facing each other across gaps up to this
  double fit_radius_edges = kDefaultFitRadiusEdges;  // at least; see kFitRadiusWidths
  bool restrict_orientation = true;
  /// The orientation is restricted only where the surface tilts more than this against the base
  /// (radians; the thesis' 11 degrees): below it the base direction means little.
  double restriction_min_tilt = 11.0 * 3.14159265358979323846 / 180;
  // Two-dimensional hysteresis: strong points seed, weak points connected to them are kept.
  double strong_error = 0.5, weak_error = 0.8;  // normalised fit error, at most
  double strong_angle = 0, weak_angle = 0;      // tilt, radians, at least; 0: automatic
  Progress progress = nullptr;
  /// Throws InputError naming the first parameter out of its range.
  void validate() const;
};

/// What another stage supplies to the detector besides the user's choices (the multi-scale
/// detector of chapter 5 on its optimally smoothed surface). Every per-vertex input is empty
/// (not given) or holds one value per vertex; the default guidance changes nothing.
struct ReliefEdgeGuidance {
  /// A base surface, per vertex: its unit normals replace the estimated base normals, and G is
  /// measured over its shape operator (world coordinates), g^T (II - II_base) g — the curvature
  /// of the local image alone (thesis fig. 4.2). On a curved base a wide soft step's curvature
  /// crosses zero where it cancels the base's, off the step's centre (4 edge lengths on the test
  /// cylinder, radius 286 edge lengths, for a step 10 edge lengths wide).
  std::vector<Vec3> base_normals;
  std::vector<Mat3> base_shape;
  /// The noise tilt where the surface was smoothed by different amounts (radians): strong points
  /// must tilt more, weak ones half as much, besides the global thresholds; the global noise
  /// tilt is then not applied.
  std::vector<double> noise_tilt;
  /// Without noise_tilt: a noise patch carrying the scan's estimated noise (a run's, shared by
  /// its stages) to measure the noise tilt on instead of building one; empty: none.
  NoisePatch noise_patch;
  /// The width of the features (mesh units): the fit-error radius is at least kFitRadiusWidths x it.
  std::vector<double> feature_width;
  /// Keep only the crossings where the slope is steepest (G rising up the slope, g), not those
  /// where it is least steep (between two steps, or a wide step's noise wiggles).
  bool steepest_only = false;
  /// The crossings' strength is the tilt across the edge (the slope along g: asin of the base
  /// normal's tangential part along g) instead of the whole tilt: a seam or wiggle crossing a
  /// slope tilts with the slope, not across itself.
  bool tilt_across = false;
};

/// The per-vertex relief-edge fields (steps 1-5: scale, curvature, base, edge model, smoothing);
/// what the prominent field (chapter 6) needs, without the curves.
struct ReliefEdgeFields : ScaledCurvature {  // scale, noise, pre-smoothing used, curvature
  BaseNormals base;
  std::vector<Vec3> direction;    // #V g: unit tangent perpendicular to the edge, pointing up the step
  std::vector<double> G;          // #V g^T II g after edge smoothing
  std::vector<double> alpha;      // #V edge intensity alpha (eq. 4.14), 1/length^2
  std::vector<double> fit_error;  // #V normalised fit error (eq. 4.7 / ||S||^2)
  std::vector<double> angle;      // #V angle between surface and base normal, radians
  double window = 0;              // orientation window w, radians
  double base_scale = 0, edge_smoothing = 0, fit_radius = 0;  // used, mesh units
  double feature_width = 0;       // feature_width() of the pre-smoothed surface, mesh units
};

/// The hysteresis thresholds on the tilt, from the zero crossings of G (step 6).
struct ReliefEdgeThresholds {
  double strong_angle = 0, weak_angle = 0;  // hysteresis tilts used, radians
  double automatic_angle = 0;     // automatic_curve_threshold of the crossing tilts
  double noise_angle = 0;         // noise_tilt: what the estimated noise alone tilts the surface by
  double steepest_crossing = 0;   // the steepest edge crossing seen, radians (to explain an empty result)
};

struct ReliefEdgeResult : ReliefEdgeFields, ReliefEdgeThresholds {
  double min_length = 0;          // used, mesh units
  int links = 0;                  // gaps bridged (link_gaps)
  Polylines edges;
};

/// Strong relief-edge seeds must tilt at least this multiple of the 99th percentile of the noise's
/// tilt: seeds grow through every weak (half as steep) segment joined to them, so the 1 % of
/// noise above the percentile grew into networks at one edge length of smoothing (precision
/// 0.35-0.54 at 1x, 0.60-0.98 at 1.5x, 0.95-1.00 at 2x on the noisy synthetic reliefs).
constexpr double kNoiseTiltFactor = 2.0;

/// The tilt (radians) that noise of the estimated level leaves after the same pre-smoothing:
/// kNoiseCurvePercentile of the normals' tilt on noise_patch, x kNoiseTiltFactor.
double noise_tilt(const NoiseEstimate& noise, double presmoothing_edges, int patch_cells = 100);
/// The same on a noise patch the caller keeps, so that a run measuring the tilt at several
/// pre-smoothings builds one patch.
double noise_tilt(const NoisePatch& patch, double presmoothing_edges);

/// The fit-error radius and the automatic base scale follow the features' own width (feature_width)
/// where it spans more than a few triangles: radius at least kFitRadiusWidths x the width, base
/// scale at least kBaseScaleWidths x the width (the thesis: three times the feature scale). With
/// fixed edge-length multiples alone, the same relief meshed at 4 M faces (16 edge lengths wide
/// instead of 2.5) lost every edge: the step no longer fitted within 4 edge lengths, and the base
/// followed the relief.
constexpr double kFitRadiusWidths = 2.4;
constexpr double kBaseScaleWidths = 9.0;


/// Steps 1-5: the per-vertex fields.
ReliefEdgeFields compute_relief_edge_fields(const Surface& surface, const ReliefEdgeParams& params = {},
                                            const ReliefEdgeGuidance& guidance = {});
/// The zero crossings of the fields' G along g: every candidate relief-edge point, its strength
/// the tilt against the base (across the edge with guidance.tilt_across).
Polylines relief_edge_crossings(const Surface& surface, const ReliefEdgeFields& fields,
                                const ReliefEdgeGuidance& guidance = {});
/// Step 6: the hysteresis tilts, automatic from `crossings` and the noise unless the user set them.
ReliefEdgeThresholds relief_edge_thresholds(const Surface& surface, const ReliefEdgeFields& fields,
                                            const Polylines& crossings, const ReliefEdgeParams& params = {},
                                            const ReliefEdgeGuidance& guidance = {});

/// The fields, their crossings, the thresholds and the curves the hysteresis keeps (step 7).
ReliefEdgeResult compute_relief_edges(const Surface& surface, const ReliefEdgeParams& params = {},
                                      const ReliefEdgeGuidance& guidance = {});
ReliefEdgeResult compute_relief_edges(const TriMesh& mesh, const ReliefEdgeParams& params = {},
                                      const ReliefEdgeGuidance& guidance = {});

}  // namespace reliefkit
