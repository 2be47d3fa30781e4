// ReliefKit — the prominent field and what it is used for (thesis chapter 6; M. Kolomenkin, I.
// Shimshoni, A. Tal, "Prominent field for shape processing and analysis of archaeological
// artifacts", IJCV 2011).
//
// The prominent direction r_p (def. 6.3.1) is perpendicular to the relief's features: the relief
// direction g (chapter 4) near relief edges, the direction of largest |curvature| t near ridges and
// valleys, blended by alpha_p (eq. 6.2). The prominent field s is the smoothest direction field that
// matches r_p where the confidence beta_p (eq. 6.4) says p is a feature point (eqs. 6.3, 6.6).
//
// Directions of principal curvature have no sign, so s is solved as a line field: in the tangent
// frame of every vertex a direction of angle phi is the complex number z = exp(2 i phi) (the
// doubled-angle representation of Knöppel, Crane, Pinkall, Schröder, "Globally optimal direction
// fields", SIGGRAPH 2013), and neighbouring frames are related by the rotation that carries one
// tangent plane onto the other (fig. 6.6), applied twice. The plain vector system of eq. 6.6
// (angle applied once) is kept as FieldRepresentation::Vector for comparison: there the two signs
// a principal direction can take cancel (tests/unit/prominent/test_prominent.cpp measures it).
//
// One sparse Hermitian positive-definite solve, one complex unknown per vertex (solve_hpd,
// reliefkit/base/solvers.h):
//   minimise  sum_edges w_pj |z_p - T_pj z_j|^2 + sum_p lambda beta_p A_p |z_p - r_p|^2,
// w_pj the cotangent weights (eq. 6.5, clamped at zero), A_p the vertex area, lambda =
// constraint_weight / (edge length)^2: beta_p = 1 holds the field at r_p (eq. 6.3's first line,
// softly, so that the noise of r_p on the features is smoothed too), beta_p = 0 leaves it harmonic.
#pragma once

#include "reliefkit/demarcating/demarcating.h"
#include "reliefkit/relief_edges/relief_edges.h"
#include "reliefkit/base/solvers.h"

namespace reliefkit {

enum class FieldRepresentation {
  Line,    // doubled angle: s and -s are the same direction (default)
  Vector,  // eq. 6.6 as written: the field is a vector field
};

struct ProminentFieldParams {
  static constexpr double kDefaultTheta = 2.0;             // eq. 6.4 (thesis: "2 gives good results")
  static constexpr double kDefaultConstraintWeight = 1.0;  // lambda x (edge length)^2; see prominent.md
  CurvatureEstimator estimator = CurvatureEstimator::Jet;
  Length presmoothing = Length::automatic();
  Length base_scale = Length::automatic();
  /// eq. 6.4's threshold. The thesis compares the step model's unnormalised residual eps_r with
  /// theta / l; that residual grows with the relief's size (on the disc relief it is largest at the
  /// step's centre, 33 x kappa_0 / 3, and smallest on flat ground, 0.8), so here a vertex is a
  /// relief-edge point where chapter 4's normalised fit error is at most kFeatureFitError and it
  /// tilts against the base by at least (2 / theta) x the weak relief-edge tilt, and a ridge/valley
  /// point where |k| > 2 and max |kappa| > (2 / theta) x kappa_0: theta = 2 keeps the automatic
  /// thresholds, a larger theta takes fainter features (the thesis' sense of theta).
  double theta = kDefaultTheta;
  double constraint_weight = kDefaultConstraintWeight;
  FieldRepresentation representation = FieldRepresentation::Line;
  Progress progress = nullptr;
  /// Throws InputError naming the first parameter out of its range.
  void validate() const;
};

struct ProminentFieldResult : ScaledCurvature {  // scale, noise, pre-smoothing, curvature
  BaseNormals base;
  double base_scale = 0;                 // used, mesh units
  double feature_width = 0;              // the features' width (reliefkit/base/curvature.h feature_width), mesh units
  std::vector<Vec3> relief_direction;    // g: across the relief edge, up the step (chapter 4)
  std::vector<Vec3> principal;           // t: direction of the largest |curvature|
  std::vector<double> alpha;             // eq. 6.2
  std::vector<double> beta;              // eq. 6.4: 1 at feature points, else 0
  std::vector<double> fit_error;         // chapter 4's normalised step-model fit error, in [0, 1]
  std::vector<double> tilt;              // angle between surface and base normal, radians
  std::vector<Vec3> prominent;           // r_p (def. 6.3.1), unit
  std::vector<Vec3> field;               // s: the prominent field, unit tangent vectors
  std::vector<double> strength;          // |z| before normalisation, in [0, ~1]: 1 on consistent features
  double curvature_threshold = 0;        // kappa_0: the "3 / l" of eqs. 6.2 and 6.4 (see prominent.md)
  double tilt_threshold = 0;             // least tilt of a relief-edge point, radians
  long long ridge_points = 0, edge_points = 0;  // beta = 1 by the curvature test / the step-model test
  long long unreached = 0;               // vertices no feature reaches (field = r_p there)
  SolveReport solve;
  double field_seconds = 0;              // the field stage alone: constraints, system, solve, normalisation
};

/// kappa_0 is this percentile of max(|k1|, |k2|) over the vertices that count: the thesis' fixed
/// 3 / l is a radius of a third of an edge, which no vertex of the bundled scans reaches.
constexpr double kFeatureCurvaturePercentile = 0.9;
/// Largest normalised fit error of a relief-edge point (Relief Edges' default for strong seeds).
constexpr double kFeatureFitError = 0.5;

/// Chapter 4's per-vertex relief-edge fields (compute_relief_edge_fields; no curves), r_p, beta_p
/// and the smooth field, on the run's Surface.
ProminentFieldResult compute_prominent_field(const Surface& surface, const ProminentFieldParams& params = {});
ProminentFieldResult compute_prominent_field(const TriMesh& mesh, const ProminentFieldParams& params = {});

/// The smooth-field stage alone (eqs. 6.3, 6.6), for callers that have r_p and beta_p: tangent
/// frames (normal, e1) per vertex, r_p and beta_p per vertex. The surface's clamped cotangent
/// Laplacian (the base normals' own) gives the weights and areas. Writes field, strength,
/// unreached, solve of `out`.
void solve_prominent_field(const Surface& surface, const std::vector<Vec3>& normal, const std::vector<Vec3>& e1,
                           const std::vector<Vec3>& target, const std::vector<double>& beta, double weight,
                           FieldRepresentation representation, ProminentFieldResult& out);

// ---- Enhancement (thesis 6.4) ----

/// At strength 1 the flow moves a vertex back to the scan where step 1 rounded it (step 1's move
/// averaged over sigma_c) and beyond by at most this many standard deviations of the scan's noise:
/// what the noise could have hidden. On noisy copies of reliefs whose clean surface is known (steps
/// 1 and 2.6 edge lengths wide, 10 and 20 % noise) the steepest slope is then 0.98-1.13 of the
/// clean one's (unbounded: 1.44-2.06; 0.35 gave up to 1.18; docs/prominent.md).
constexpr double kFlowNoiseMoves = 0.25;

struct EnhanceParams {
  static constexpr double kDefaultSpatialEdges = 1.5;  // sigma_c, x edge length
  static constexpr int kDefaultBilateralIterations = 2;
  static constexpr int kMaxFlowIterations = 100;        // the automatic stop's safety net
  ProminentFieldParams field;
  Length spatial_scale = Length::automatic();  // sigma_c; sigma_s = 0.5 sigma_c, sigma_r = 0.4 sigma_c
  int bilateral_iterations = kDefaultBilateralIterations;
  /// Inverse-curvature-flow iterations; -1: until every vertex has stopped (automatic).
  int flow_iterations = -1;
  /// Largest move per flow iteration, x edge length.
  double flow_step = 0.2;
  /// How far the flow may move a vertex, x the lesser of what the data supports (back to the scan
  /// where step 1 rounded it, then kFlowNoiseMoves x the noise's standard deviation) and the height
  /// its initial curvature kappa explains over the stopping rule's radius rho (0.5 |kappa| rho^2). 1: no steeper than the scan supports (a noise-free scan is left as
  /// step 1 makes it); about 12 restores what wear took from a step (steeper than the scan shows:
  /// an illustration, not a measurement); the local height extremum still bounds every vertex.
  double strength = 1.0;
  /// Use the prominent term exp(-r_j^2 / 2 sigma_r^2) in the bilateral filter (off: Fleishman et al.).
  bool prominent_term = true;
  Progress progress = nullptr;
  void validate() const;
};

struct EnhanceResult {
  ProminentFieldResult field;
  double spatial_scale = 0;            // sigma_c used, mesh units
  double extremum_radius = 0;          // the neighbourhood of the stopping rule, mesh units
  std::vector<Vec3> bilateral;         // positions after step 1
  std::vector<Vec3> positions;         // after step 2 (the result)
  std::vector<double> height_change;   // step 2's move along the base normal, mesh units
  int flow_iterations = 0;             // run
  long long at_extremum = 0;           // vertices stopped by the local height extremum
  long long at_curvature_cap = 0;      // stopped by the height their initial curvature explains
  bool converged = false;              // the automatic stop was reached (every vertex stopped)
  double bilateral_seconds = 0, flow_seconds = 0;
};

/// The prominent field of the surface, then the bilateral filter along it and the flow.
EnhanceResult enhance_relief(const Surface& surface, const EnhanceParams& params = {});
EnhanceResult enhance_relief(const TriMesh& mesh, const EnhanceParams& params = {});

/// One bilateral pass (eqs. 6.7-6.8) of the positions of `at` (the run's surface, or a smoothed
/// copy of it by with_positions): neighbours within 2 sigma_c along the surface; the new positions.
/// `field` null: the filter of Fleishman et al. 2003.
std::vector<Vec3> bilateral_pass(const Surface& at, double sigma_c, const std::vector<Vec3>* field);

// ---- Coloring (thesis 6.5) ----

enum class ColoringCurvature { Prominent, Mean, Maximal };

struct ColoringResult {
  std::vector<double> curvature;  // the curvature coloured (kappa_p for Prominent), 1/length
  std::vector<double> grey;       // 0.5 + atan(lambda kappa) / pi, in (0, 1)
  double lambda = 0;              // used (mesh units)
};

/// grey = 0.5 + atan(lambda kappa) / pi (eq. 6.9 mapped to [0, 1]); lambda = contrast / kappa_ref,
/// kappa_ref the 90th percentile of |kappa| over the vertices that count (all if `counts` is empty):
/// the same colours for the same object in any unit.
ColoringResult arctan_coloring(std::vector<double> curvature, const std::vector<char>& counts, double contrast);

/// kappa_p = the normal curvature along `field` (Prominent; unit tangents per vertex), or the mean or
/// the signed largest curvature, coloured by arctan_coloring.
ColoringResult curvature_coloring(const Curvature& curvature, const std::vector<Vec3>* field,
                                  const std::vector<char>& counts, ColoringCurvature which, double contrast);

}  // namespace reliefkit
