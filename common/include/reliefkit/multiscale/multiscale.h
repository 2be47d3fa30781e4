// ReliefKit — multi-scale curves (thesis section 5.4): the optimal scale of every vertex
// (reliefkit/multiscale/optimal_scale.h), the optimally smoothed surface, and the single-scale detectors run
// on it without pre-smoothing of their own; the curves are placed back on the input mesh (each
// point keeps its mesh edge and its parameter along it).
#pragma once

#include "reliefkit/multiscale/optimal_scale.h"
#include "reliefkit/relief_edges/relief_edges.h"
#include "reliefkit/relief_edges/ridges.h"

namespace reliefkit {

struct MultiscaleRidgeValleys {
  OptimalScale scale;        // per-vertex scale and the smoothed surface the curves come from
  RidgeValleyResult curves;  // ridges and valleys, on the input mesh; strengths and thresholds
                             // normalised (unit-free: (σ / h)² |k| h)
};

struct MultiscaleReliefEdges {
  OptimalScale scale;
  ReliefEdgeResult curves;   // edges on the input mesh; per-vertex fields of the smoothed surface
  double noise_angle = 0;    // the smallest per-vertex noise tilt (at the largest scale; radians)
};

/// Multiplies each curve point's strength by (σ / h)^{2γ} h^power, σ the scale the smoothed surface
/// holds at the smaller scale of the two ends of the point's edge (OptimalScale::smoothed_ratio x
/// it, at least the smallest level; the larger end would amplify a fine feature's curvature where
/// the scale changes across the edge): the strength normalised as in the scale selection,
/// unit-free for power = 1 (curvature) or 2 (curvature derivative).
void normalise_curve_strengths(Polylines& curves, const OptimalScale& scale, double gamma, int power);

/// Curves (chains at least the minimum length) must be this share of the strength noise reaches
/// at 99 % of the vertices (OptimalScale::strength_floor).
constexpr double kCurveNoise = 0.75;

/// A Gaussian groove's banks are ridges of the surface with 0.45 times the groove's curvature
/// (and a crest's feet valleys): curves of the opposite kind within a feature's footprint
/// (OptimalScale::sign, dominant_reach) that are less than this share of its strength are its
/// banks, reported as the feature itself (its centre line) and not again.
constexpr double kBankRatio = 0.5;
/// Drops the segments both of whose points lie in the footprint of a feature of `flanked_sign`
/// (+1 convex: drops valleys along crests; -1 concave: ridges along grooves) weaker than kBankRatio x it.
void drop_banks(Polylines& curves, const OptimalScale& scale, int flanked_sign);

/// Per vertex, the tilt noise leaves on the optimally smoothed surface (noise_tilt at each level's
/// scale combined with the final smoothing, interpolated log-linearly in log σ at the vertex's scale).
/// Simulated on the run's noise patch (scale.noise_patch) when it carries the scan's noise, else on
/// one patch built here for all levels.
std::vector<double> noise_tilt_at_scales(const OptimalScale& scale, double final_smoothing_edges, long long faces);

/// Per-vertex scales draw each place at one scale: where a fine feature lies beside or on a wide one
/// (lettering on a coin's field, an eye on a cheek) it can be smoothed away or fall under the
/// threshold the wide features set (the thesis' recipe alone kept 0.39-0.61 of the single-scale
/// relief edges' length on the shared scans and decimated copies, docs/multiscale.md). So the multi-scale filters join
/// two readings: the single-scale detector's at its automatic pre-smoothing (the finest significant
/// scale) and the optimal scale's. Curves of one are added to the other's where none of the other's
/// lies within kSameEdgeEdges edge lengths (the same feature read at two scales), after the finest
/// reading's blurred flanks are dropped: its curves within kFlankReach x its pre-smoothing of the
/// optimal scale's (drop_blurred_flanks). Both readings are kept wherever they are drawn, whatever
/// scale was selected there: an earlier rule that kept the finest reading only where the selected
/// scale was under 6 edge lengths kept 0.28 of the single scale's length on the Cycladic torso
/// and 0.16 on the oxhide ingot, where wide scales were selected nearly everywhere (the two sides
/// of a carved groove became one line); its reason, off-centre pieces of a wide soft step at 20 %
/// noise, no longer shows (the sharp band and soft step test: recall and precision 1.00 without it).
constexpr double kSameEdgeEdges = 2.0;
constexpr double kFlankReach = 2.0;
/// Adds to `curves` the segments of `other` (the other reading) farther than kSameEdgeEdges edge
/// lengths from them; chains under min_length dropped.
void add_other_scale(Polylines& curves, const Polylines& other, double edge, double min_length);
/// Drops the segments of `finest` within kFlankReach x `sigma` of `near`, then its chains under min_length.
void drop_blurred_flanks(Polylines& finest, const Polylines& near, double sigma, double min_length);
/// Relief edges: the optimal scale's, and the finest scale's added (params as the user chose,
/// pre-smoothing automatic).
void add_finest_scale_edges(const Surface& surface, ReliefEdgeParams params, const OptimalScale& scale,
                            ReliefEdgeResult& multi);
/// Ridges and valleys: the finest scale's (strengths normalised as the multi-scale ones, σ the
/// pre-smoothing, at least the smallest scale), and the optimal scale's added.
void add_finest_scale_lines(const Surface& surface, RidgeValleyParams params, const OptimalScale& scale,
                            RidgeValleyResult& multi);

/// The multi-scale ridges and valleys are connected lines: segments down to this share of the
/// threshold joined to stronger ones are kept, gaps up to this many edge lengths bridged, and the
/// filter's default minimum length is kMultiscaleMinLengthEdges (the thresholds alone left 19-63 %
/// of the length in pieces under 10 edge lengths on the shared scans and decimated copies).
constexpr LineLinking kConnectingLines{0.5, 6.0};
constexpr double kMultiscaleMinLengthEdges = kDashEdges;

/// `scale.curve` is set to the detector's strength; `params.presmoothing` is ignored (the optimal
/// scale replaces it). The run's `surface` gives the scan's topology, scale and noise. Ridges and
/// valleys are drawn on the optimally smoothed surface as surface.with_positions(...); the relief
/// edges' detector gives that surface its own scale and noise (its lengths are in the smoothed
/// surface's median edge, as before the run's Surface; see docs/multiscale.md).
MultiscaleRidgeValleys multiscale_ridges_valleys(const Surface& surface, OptimalScaleOptions scale,
                                                 RidgeValleyParams params = {});
MultiscaleReliefEdges multiscale_relief_edges(const Surface& surface, OptimalScaleOptions scale,
                                              ReliefEdgeParams params = {});
/// The same over a mesh of the caller's (tests, benchmarks).
MultiscaleRidgeValleys multiscale_ridges_valleys(const TriMesh& mesh, OptimalScaleOptions scale,
                                                 RidgeValleyParams params = {});
MultiscaleReliefEdges multiscale_relief_edges(const TriMesh& mesh, OptimalScaleOptions scale,
                                              ReliefEdgeParams params = {});

}  // namespace reliefkit
