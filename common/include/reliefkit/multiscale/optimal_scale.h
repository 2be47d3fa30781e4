// ReliefKit — the optimal scale of every vertex and the optimally smoothed surface (thesis
// chapter 5, sections 5.3–5.5).
//
// 1. Scale space (reliefkit/multiscale/scale_space.h): the surface diffused to Gaussian scales σ from
//    `min_scale_edges` to `max_scale_edges` edge lengths, `levels_per_octave` per doubling.
// 2. Strength f per vertex and level: ridges & valleys f = max(|k1|, |k2|) (sect. 5.5.1) of the
//    feature alone — the shape operator minus that of the base surface (the surface at twice the
//    largest scale), since on a curved object the base's own curvature makes t^γ |k| grow without
//    bound;
//    relief edges f = the curvature derivative across the edge, max over directions u of
//    C(u, u, u) (sect. 5.5.2). The selected scale is where t^γ f peaks, t = σ² (eq. 5.2), refined
//    in log t (reliefkit/multiscale/scale_selection.h). The argmax does not change when f is multiplied by a
//    constant and the levels are edge-length multiples, so the selection is independent of the
//    mesh's unit and, for relief edges, of the relief's height (eq. 5.15 is not: it assumes a
//    unit-height step; see scale_selection.h).
// 2b. Dominant scale: eq. 5.2 at a point on the flank of a groove selects a larger scale than at
//    its centre (the groove's curvature reaches the flank only when smoothed) and the shoulders
//    again a smaller one; positions from such different scales side by side drew false ridges
//    along the flanks (on the test cylinder: at ±6 edge lengths from a valley 4.4 wide, 3.5x as
//    strong as the threshold). So each vertex takes the selection of the strongest vertex within
//    `dominant_reach` x that vertex's own scale (its footprint), by bounded propagation.
// 3. Fill (eq. 5.3): the scale must equal the selection where the strength is high and vary
//    smoothly elsewhere. Solved for u = log σ as the least-squares problem
//      min Σ_v m_v ρ_v (u_v − û_v)² + μ uᵀ K u + ε Σ_v m_v (u_v − u_max)²  (μ: fill_smoothness),
//    m the vertex areas / h², K the cotangent stiffness (the Laplacian of eq. 5.4), ρ_v = (a f̃_v)²
//    with a f̃_max = 9 the thesis' weight 1 / w = 1 + a f taken above the median strength
//    (f̃ = max(0, f − median f): the median vertex carries no feature, only noise, whose strength
//    peaks at the finest level). The ε term sends featureless areas to the largest scale over a
//    few edge lengths (noise there is smoothed away; no curve is lost, since there is none) and
//    keeps the system well conditioned. One sparse SPD solve (reliefkit/base/solvers.h), not SVD.
// 3b. Bounded growth: the filled scale rises by at most `max_scale_growth` edge lengths of σ per
//    edge length of distance from any vertex (σ_v <= σ_u + g |uv|; the largest field that holds
//    it). Where it rose from a fine feature's scale to nearly the largest within a few edge
//    lengths, the vertices beside the feature read the coarse levels, which hold the feature
//    itself blurred: the assembled surface rose again beside it, and a false valley ran along
//    each fine ridge (and a false ridge along each fine valley) a few edge lengths away. With
//    g = 0.5 the blurred tail falls monotonically away from the feature. Measured with
//    `bench_multiscale --family` (docs/multiscale.md): precision 0.51 -> 0.88 (widths 3x apart),
//    0.52 -> 0.81 (6x); the 14x test 0.958 -> 0.963.
// 4. Optimally smoothed surface (sect. 5.4): each vertex takes its position at its own scale
//    (interpolated in log σ between the two levels around it; the levels' displacements are kept
//    in single precision), then a light diffusion of `final_smoothing_edges` removes the seams.
//    Ridges & valleys read it at their feature's own width, not at the selected scale: γ = 1
//    selects √2 x a Gaussian line's width, where a wide line's crest is flat and its position
//    wanders (see ridge_detection_ratio).
#pragma once

#include <memory>
#include <vector>

#include "reliefkit/base/curvature.h"
#include "reliefkit/base/mesh.h"
#include "reliefkit/base/noise_patch.h"
#include "reliefkit/base/scale.h"
#include "reliefkit/multiscale/scale_space.h"
#include "reliefkit/base/solvers.h"
#include "reliefkit/base/surface.h"
#include "reliefkit/base/zero_crossings.h"

namespace reliefkit {

/// Selections within this many rings of a boundary (one-sided neighbourhoods) anchor no scale.
constexpr int kBorderRings = 3;

/// The object (its largest part's bounding-box diagonal) must span this many smallest scales; the
/// largest scale is lowered to a this-many-th of it when asked for more (the base surface, at
/// twice the largest scale, would otherwise smooth the object flat).
constexpr double kMinObjectScales = 8.0;

/// An anchor's own strength is at least this share of the strongest selection reaching it: the
/// centre line of a feature (its strength varies along it by noise), not its banks (0.45).
constexpr double kAnchorShare = 0.8;

/// A selection anchors a scale only if it is this many times what noise reaches at its scale
/// (OptimalScale::level_noise, the noise's 99th percentile).
constexpr double kSignificance = 2.0;

/// Implicit scale-space steps per doubling of the diffusion time in the optimal-scale pass for
/// ridges & valleys (relief edges keep the scale space's 4; see optimal_scale.cpp).
constexpr int kOptimalScaleSubsteps = 2;

enum class ScaleStrength { RidgesValleys, ReliefEdges };

/// The base surface is the surface smoothed to this many times the largest scale: for ridges &
/// valleys twice; for relief edges four times, since the multi-scale relief-edge detector measures
/// the tilt and G over it — at twice, a wide soft step (tanh width 8 edge lengths, selected at 10)
/// kept 2.7 degrees of its 6 over a base that followed it, under the automatic threshold (recall
/// 0.00; at four times 1.00). The object must then span 4 largest scales (kMinObjectScales: 8).
constexpr double kRidgeBaseFactor = 2.0;
constexpr double kReliefBaseFactor = 4.0;

/// μ of eq. 5.3 (below, OptimalScaleOptions::fill_smoothness): the scale field's smoothness.
/// Relief edges: where the scale changes along a feature the assembled surface shows a seam, and
/// relief edges (third derivatives) follow the seams. A step's t C is flat around its peak in log t, so the
/// anchors along one wide soft step selected anywhere from 8.9 to 12.4 edge lengths; on the test
/// relief (a sharp narrow band and a soft step 8 edge lengths wide) the relief edges' precision
/// was, for μ = 1 / 100 / 1000 / 10000: 0.61 / 1.00 / 1.00 / 0.95 at 20 % noise and
/// – / 0.56 / 0.96 / 1.00 at 2 % (fewer anchors are significant in strong noise, so the seams
/// show most on clean scans like the coin). With (a f)² ≤ 81 at the strongest anchors, the scale
/// still changes within about 3.5 edge lengths (√(μ / 81)) from a fine to a coarse feature.
/// Ridges & valleys keep μ = 1: F1 0.985 (μ = 1), 0.991 (100), 0.992 (1000), but at μ = 1000
/// the fill needs a Cholesky factorisation (3.8 s at 1 M faces instead of conjugate gradients'
/// fraction of a second).
constexpr double kReliefFillSmoothness = 1000.0;
constexpr double kRidgeFillSmoothness = 1.0;

/// Noise below this share of the edge length counts as this much in the scale selection's
/// significance test (level_noise): on a noise-free mesh every local maximum of t^γ f anchored a
/// scale (the soft step's tails too), and the seams between them drew false relief edges
/// (relief edges' precision 0.74 at no noise; with this floor 0.98). The coin's scan measures 2.0 %.
constexpr double kMinScaleNoise = 0.02;

/// γ for ridges & valleys: the thesis' 1 (selects √2 x a Gaussian ridge's width).
constexpr double kRidgeGamma = 1.0;
/// γ for relief edges: 1, as for ridges (selects √2 x a smoothed step's width; eq. 5.15 needs
/// γ < 1.3). With γ = 1 the normalised strength t C of a smoothed step peaks at 0.15 x its slope
/// (height / width): a wide soft step of slope 0.7 is then no stronger than 20 % noise at one edge
/// length (0.1-0.24) and anchors no scale. γ = 1.25 lifts such steps (0.35, selected at √5 x their
/// width) but lost the disc reliefs (recall 0.08-0.21 on the cylinder); see docs/multiscale.md.
constexpr double kReliefEdgeGamma = 1.0;

/// The normalised strength t^γ f of a Gaussian line of width w peaks at σ = w √(γ / (1.5 − γ))
/// (√2 w for γ = 1): the selection's bias, not the line's size. Ridges & valleys are drawn on the
/// surface at the line's own width, this share of the selected scale (√((1.5 − γ) / γ); the
/// scale γ = 3/4 would select, as Lindeberg's ridge detection does). At the selected scale a
/// wide line's crest is flat and its curvature extremum wanders, and a wide shallow valley on a
/// curved object no longer bends it inwards: Multiscale.WideGroovesOnACurvedObjectAreReadAtTheirOwnWidth
/// reads coarse recall 0.886 -> 0.930, precision 0.669 -> 0.806; the width-ratio family
/// (bench_multiscale --family) mean F1 0.828 -> 0.863. Relief edges keep the selected scale (1).
double ridge_detection_ratio(double gamma);

/// With the largest scale left automatic (OptimalScaleOptions::max_scale_auto), it is at most the
/// object's size (bounding-box diagonal of its largest part) over this: on a small curved object
/// the object's own shape is the strongest "feature" at large scales, and at 16 edge lengths the
/// Stanford bunny (171 edge lengths across) and the fertility statuette (124) selected 11.3 at
/// 90-100 % of their vertices and kept 29-671 curve segments; at 4-5 their relief edges are like
/// the single-scale filter's. The coin (321 across) gets 10.
constexpr double kAutoMaxScaleObjectFraction = 32.0;

struct OptimalScaleOptions {
  ScaleStrength curve = ScaleStrength::RidgesValleys;
  double min_scale_edges = 1, max_scale_edges = 16;  // the range of σ, in edge lengths
  bool max_scale_auto = false;  // max_scale_edges is the automatic default: lowered on small objects
  int levels_per_octave = 2;                          // scales per doubling of σ
  /// The normalisation t^γ; 0: the curve type's default (kRidgeGamma, kReliefEdgeGamma). A
  /// single peak needs γ < 1.5 for ridges (eq. 5.11) and γ < 1.3 for relief edges (eq. 5.15).
  double gamma = 0;
  double effective_gamma() const {
    return gamma != 0 ? gamma : curve == ScaleStrength::ReliefEdges ? kReliefEdgeGamma : kRidgeGamma;
  }
  double fill_weight = 9.0;                           // a f_max of eq. 5.3
  double fill_smoothness = 0;                         // μ; 0: kRidgeFillSmoothness / kReliefFillSmoothness
  double effective_fill_smoothness() const {
    return fill_smoothness > 0 ? fill_smoothness
                               : curve == ScaleStrength::ReliefEdges ? kReliefFillSmoothness : kRidgeFillSmoothness;
  }
  double featureless_pull = 1e-4;                     // ε
  bool fill = true;                                   // eq. 5.3; false: the raw selection (0 where none)
  double max_scale_growth = 0.5;  // 3b: σ rises by at most this many edge lengths per edge length; 0: unbounded
  double bank_reach = 4.5;       // a feature's banks lie within this many times its scale (graph distance)
  double dominant_reach = 3.0;  // a selection covers this many times its scale; 0: per vertex (eq. 5.2 as is)
  bool smoothed_surface = false;                      // also build the optimally smoothed surface
  double final_smoothing_edges = 0.5;                 // the light smoothing after assembling it
  ScaleSpaceOptions::Stepping stepping = ScaleSpaceOptions::Stepping::Auto;
  Progress progress = nullptr;
  /// Throws InputError naming the first parameter out of its range.
  void validate() const;
};

struct OptimalScale {
  MeshScale scale;               // the mesh's edge length h, the unit of the options
  std::vector<double> levels;    // σ of the levels (mesh units)
  bool max_scale_lowered = false;  // the object is too small for the asked largest scale (kMinObjectScales,
                                   // or kAutoMaxScaleObjectFraction when automatic)
  std::vector<double> selected;  // #V eq. 5.2's σ (mesh units); 0 where no level has strength
  std::vector<double> strength;  // #V normalised strength t^γ f at the selection (unit-free: f x h or h²),
                                 // the dominant one's (dominant_reach)
  std::vector<double> own_strength;  // #V the vertex's own, before dominance
  std::vector<signed char> own_sign; // #V and the sign of its own selection
  std::vector<signed char> sign;     // #V ridges & valleys: +1 the dominant feature is convex (ridge-like), -1 concave
  std::vector<double> bank_strength;     // #V the strongest feature within bank_reach x its scale
  std::vector<signed char> bank_sign;    // #V and its sign
  std::vector<double> sigma;     // #V the final scale (mesh units): filled (eq. 5.3) or = selected
  std::vector<Vec3> smoothed;    // #V the optimally smoothed surface, when asked: each vertex at
                                 // smoothed_ratio x its sigma (at least the smallest level)
  double smoothed_ratio = 1;     // ridges & valleys: ridge_detection_ratio(γ); relief edges 1
  std::vector<Mat3> base_shape;  // #V the base surface's shape operator, with the smoothed surface
  std::vector<Vec3> base_normal; // #V and its unit normals
  std::vector<double> level_noise;  // per level: what noise alone reaches (99th percentile of t^γ f on
                                    // noise_patch); strengths count above it
  NoisePatch noise_patch;        // the estimated noise, at least kMinScaleNoise
  double strength_floor = 0;     // the largest of them (fill weights, curve thresholds)
  NoiseEstimate noise;           // the scan's estimated noise
  double strength_ref = 0;       // f_max of eq. 5.3 (99.9th percentile of the strengths)
  SolveReport fill_solve;
  ScaleSpaceReport space;
  ScaleSpaceReport base_space;   // ridges & valleys: the base surface (twice the largest scale)
};

/// The scan's topology, scale and noise come from the run's `surface`; every level of the scale
/// space is surface.with_positions(...). The noise floor is simulated once, on `noise_patch`.
OptimalScale optimal_scale(const Surface& surface, const OptimalScaleOptions& options = {});
/// The same over a mesh of the caller's (tests, benchmarks).
OptimalScale optimal_scale(const TriMesh& mesh, const OptimalScaleOptions& options = {});

/// The strength of a level: max(|k1|, |k2|), or max over u of C(u, u, u).
double ridge_strength(double k1, double k2);
/// The shape operator k1 d1 d1ᵀ + k2 d2 d2ᵀ of vertex v (world coordinates).
Mat3 shape_tensor(const Curvature& c, int v);
/// max |eigenvalue| of (shape operator − base's), restricted to v's tangent plane: the curvature
/// of the feature alone. On a cylinder of radius R, |k| itself grows t^γ |k| like t / R and the
/// largest scale won everywhere (every vertex of the test cylinder selected 16 edge lengths).
double ridge_strength_over_base(const Curvature& c, int v, const Mat3& base);
/// The same eigenvalue with its sign (> 0 convex).
double signed_ridge_strength_over_base(const Curvature& c, int v, const Mat3& base);
double relief_edge_strength(const CurvatureDerivative& C);

/// Curves found on a smoothed copy (same connectivity) placed on `mesh`: each point keeps its edge
/// and its parameter along it.
void place_on_mesh(const TriMesh& mesh, Polylines& curves);

}  // namespace reliefkit
