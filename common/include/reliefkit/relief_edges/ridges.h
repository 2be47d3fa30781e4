// ReliefKit — ridges and valleys, the classic curves (thesis 3.4 and 5.5.1; Ohtake, Belyaev,
// Seidel, "Ridge-valley lines on meshes via implicit surface fitting", SIGGRAPH 2004).
//
// A ridge point is where the maximal curvature k1 > 0 has a maximum along its own direction
// t1: the derivative of k1 along t1, C(t1, t1, t1) = a, crosses zero while decreasing along t1.
// A valley point is where the minimal curvature k2 < 0 has a minimum along t2: C(t2, t2, t2) = d
// crosses zero while increasing along t2. Principal directions have no sign, so the field is
// axial (directions are aligned per face before interpolation). Strength: k1 for ridges, -k2
// for valleys (1/length).
#pragma once

#include "reliefkit/base/curvature.h"
#include "reliefkit/base/curve_selection.h"
#include "reliefkit/base/noise_patch.h"
#include "reliefkit/base/zero_crossings.h"

namespace reliefkit {

struct RidgeValleyParams {
  static constexpr double kDefaultMinLengthEdges = kDashEdges;
  CurvatureEstimator estimator = CurvatureEstimator::Jet;
  Length presmoothing = Length::automatic();  // automatic: from the noise level
  double relative_threshold = 1.0;   // x automatic threshold (automatic_curve_threshold)
  double min_length_edges = kDefaultMinLengthEdges;
  LineLinking linking = kLineLinking;
  Progress progress = nullptr;
  /// Throws InputError naming the first parameter out of its range.
  void validate() const;
};

struct RidgeValleyResult : ScaledCurvature {  // scale, noise, pre-smoothing used, curvature
  Polylines ridges, valleys;
  double min_length = 0;                             // used, mesh units
  double ridge_threshold = 0, valley_threshold = 0;  // absolute |k| thresholds used, 1/length
  double strongest_ridge = 0, strongest_valley = 0;  // strongest crossings seen (to explain empty layers)
};

/// Ridges or valleys from an existing curvature (with derivatives); threshold absolute.
Polylines ridge_lines(const TriMesh& mesh, const Curvature& c, bool valleys, double min_strength);
/// The same, with the strengths of all crossing segments (CandidateCrossings).
CandidateCrossings ridge_candidates(const TriMesh& mesh, const Curvature& c, bool valleys, double min_strength);


/// What noise alone draws: the least thresholds (ridges, valleys) at which the lines of a noise
/// patch (noise_patch(.., n), carrying the scan's noise), after the same pre-smoothing and the
/// same selection (`params`' hysteresis, gaps, minimum length), keep no line in its interior;
/// unit-free (|k| x edge length). The automatic thresholds stay above them.
struct RidgeStrengths {
  double ridges = 0, valleys = 0;
};
RidgeStrengths noise_ridge_strengths(const NoisePatch& patch, double presmoothing_edges,
                                     const RidgeValleyParams& params);

/// `noise_patch` (optional): the scan's relative noise at noise_patch_cells(faces) if the caller
/// has one; otherwise one is made when the scan's noise is above kCleanNoise.
RidgeValleyResult compute_ridges_valleys(const Surface& surface, const RidgeValleyParams& params = {},
                                         const NoisePatch& noise_patch = {});
RidgeValleyResult compute_ridges_valleys(const TriMesh& mesh, const RidgeValleyParams& params = {});

}  // namespace reliefkit
