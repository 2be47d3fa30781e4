// Multi-scale curves (reliefkit/multiscale/multiscale.h) against single scales, on the thesis' quantitative
// experiment made harder (sect. 5.5.1, Fig. 5.4): a noisy cylinder (normal noise of 20 % of the
// edge length) carrying valleys and ridges whose widths differ by 14 times, the finest under one
// edge length wide (a Gaussian of 0.35 edge lengths: 0.82 wide at half depth).
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>

#include "reliefkit/base/curve_selection.h"
#include "reliefkit/base/work_counts.h"
#include "reliefkit/multiscale/multiscale.h"
#include "reliefs.h"
#include "shapes.h"

using namespace reliefkit;
using rktest::AxialFeature;

namespace {

// 1,800 cells around a cylinder of radius 1: h = 0.0035, so the thesis' tolerance of 0.5 % of the
// radius is 1.4 edge lengths. The features run along the axis; the relief-edge bands are read as
// well on a cylinder of 29 rows (104 K faces, scored on 22 rows away from the ends) as on the
// ridges' 72 rows, where a short one would let a single scale come within 0.15 of multi-scale F1.
constexpr int kAround = 1800;
constexpr double kLength = 0.25, kBandLength = 0.1, kTolerance = 0.005;

struct Score {
  const char* name;
  double fine = 0, coarse = 0;  // mean recall of the fine and of the coarse features
  double precision = 0, f1 = 0;
};

void print(const Score& r) {
  std::printf("  %-22s recall fine %.4f coarse %.4f  precision %.4f  F1 %.4f\n", r.name, r.fine, r.coarse,
              r.precision, r.f1);
}

double f1(double recall, double precision) {
  return recall + precision > 0 ? 2 * recall * precision / (recall + precision) : 0;
}

// Scores and prints ridges and valleys against the cylinder's fine and coarse lines.
Score score_lines(const rktest::AxialCylinder& cyl, const char* name, const Polylines& ridges,
                  const Polylines& valleys) {
  const rktest::FineCoarseScore s = rktest::score_fine_coarse(cyl, ridges, valleys, kTolerance, 3 * cyl.edge);
  const Score r{name, s.fine, s.coarse, s.precision, s.f1()};
  print(r);
  return r;
}

// Multi-scale ridges and valleys at defaults beside the single scale at `presmoothing` edge
// lengths, on a noisy cylinder (20 %) of fine and coarse lines.
std::pair<Score, Score> multi_beside_single(double fine, double coarse, double depth, double length,
                                            double presmoothing) {
  const rktest::AxialCylinder cyl =
      rktest::axial_cylinder(rktest::fine_and_coarse_lines(kAround, fine, coarse, depth), kAround, length, 0.2);
  const MultiscaleRidgeValleys ms = multiscale_ridges_valleys(cyl.mesh, {});
  const Score multi = score_lines(cyl, "multi-scale", ms.curves.ridges, ms.curves.valleys);
  RidgeValleyParams p;
  p.presmoothing = Length::in_edges(presmoothing);
  const RidgeValleyResult r = compute_ridges_valleys(cyl.mesh, p);
  return {multi, score_lines(cyl, "single scale", r.ridges, r.valleys)};
}

}  // namespace

TEST(Multiscale, RidgesAndValleysOfWidthsFourteenTimesApartOnANoisyCylinder) {
  const std::vector<AxialFeature> features = rktest::fine_and_coarse_lines(kAround, 0.35, 5, 2);
  const rktest::AxialCylinder cyl = rktest::axial_cylinder(features, kAround, kLength, 0.2);
  std::printf("cylinder: %d faces, edge %.5f, tolerance %.2f edge lengths\n", cyl.mesh.n_faces(), cyl.edge,
              kTolerance / cyl.edge);
  auto t0 = std::chrono::steady_clock::now();
  const MultiscaleRidgeValleys ms = multiscale_ridges_valleys(cyl.mesh, {});
  std::printf("multi-scale: %.2f s\n", std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
  const Score multi = score_lines(cyl, "multi-scale", ms.curves.ridges, ms.curves.valleys);
  double best = 0;
  for (double s : {0.0, 1.0, 2.0, 4.0, 8.0}) {
    RidgeValleyParams p;
    p.presmoothing = Length::in_edges(s);
    const RidgeValleyResult r = compute_ridges_valleys(cyl.mesh, p);
    char name[64];
    std::snprintf(name, sizeof name, "single, %.0f edge lengths", s);
    best = std::max(best, score_lines(cyl, name, r.ridges, r.valleys).f1);
  }
  const RidgeValleyResult at_defaults = compute_ridges_valleys(cyl.mesh, {});
  const Score single = score_lines(cyl, "single, defaults", at_defaults.ridges, at_defaults.valleys);
  // Measured: recall 0.991 / 1.000, precision 0.988, F1 0.992 (was asserted 0.95 / 0.95 / 0.8);
  // the single scale at its defaults (4.2 edge lengths) 0.897, the best single scale (2 edge
  // lengths, chosen knowing the answer) 0.992. The F1 >= best single + 0.15 held while the
  // single scale left noise in (best 0.61); since the single-scale filter keeps its lines above
  // what noise alone draws (noise_ridge_strengths), + 0.15 would exceed 1: multi-scale at its
  // defaults matches the best hand-chosen scale instead.
  EXPECT_GE(multi.fine, 0.98);
  EXPECT_GE(multi.coarse, 0.99);
  EXPECT_GE(multi.precision, 0.95);
  EXPECT_GE(multi.f1, best - 0.01);
  EXPECT_GE(multi.f1, single.f1 + 0.06);
}

// Grooves and crests 14 edge lengths wide, 2 deep, beside lines 1 wide, on a cylinder of radius 286
// edge lengths (20 % noise): the wide lines select about 13 edge lengths (√2 x their width), where
// a groove no longer bends the cylinder inwards and a crest's extremum wanders. Read at their own
// width (ridge_detection_ratio) they are found; the single scale finds them only when told 8.
TEST(Multiscale, WideGroovesOnACurvedObjectAreReadAtTheirOwnWidth) {
  const auto [multi, single] = multi_beside_single(1, 14, 2, kBandLength, 8);  // 8: the single scale finding them
  // Measured: recall 1.000 / 0.877, precision 0.860, F1 0.898 (single at 8: coarse 0.991, fine
  // 0.000). With pieces down to 4 edge lengths kept (the minimum length before the curve filters
  // dropped dashes under 10): coarse 0.947, precision 0.817, F1 0.888. Read at the selected scale
  // (ratio 1): coarse 0.886, precision 0.669.
  EXPECT_GE(multi.fine, 0.97);
  EXPECT_GE(multi.coarse, 0.85);
  EXPECT_GE(multi.precision, 0.8);
  EXPECT_GE(multi.f1, single.f1 + 0.15);  // 0.878 against 0.656: the single scale of the wide lines loses the fine
}

// Widths three times apart (1 and 3 edge lengths, 2 deep, 20 % noise): both kinds are found at
// almost one scale, so the risk is not missing a feature but echoes of it. Without the bounded
// growth of the filled scale (OptimalScaleOptions::max_scale_growth) the vertices beside each fine
// line read levels ten times coarser, which hold the line itself blurred: a false valley ran along
// every fine ridge a few edge lengths away (precision 0.64; bounded: 0.93).
TEST(Multiscale, NoEchoesBesideFineLinesWhereTheScaleRisesToTheBackground) {
  const auto [multi, best] = multi_beside_single(1, 3, 2, kLength, 2);  // 2: the best single scale here
  // Measured: recall 1.000 / 1.000, precision 0.998, F1 0.999 (single 0.918; read at the selected
  // scale rather than the lines' width, precision 0.927).
  EXPECT_GE(multi.fine, 0.99);
  EXPECT_GE(multi.coarse, 0.99);
  EXPECT_GE(multi.precision, 0.87);
  EXPECT_GE(multi.f1, best.f1 + 0.03);
}

namespace {
// A plate with a narrow and a wide groove and 10 % noise, in the given unit.
TriMesh grooved_plate(double unit) {
  auto groove = [](double x, double c, double s) { return -0.02 * std::exp(-(x - c) * (x - c) / (2 * s * s)); };
  TriMesh m = rktest::height_field(
      [&](double x, double y) { return groove(x, -0.4, 0.012) + groove(x + 0.3 * y, 0.4, 0.06); }, 1.0, 120, 0.3, 3);
  rktest::Rng rng(5);
  for (auto& p : m.vertices) p.z() += 0.1 * (2.0 / 120) * rng.normal(), p *= unit;
  return m;
}
}  // namespace

TEST(Multiscale, SameScalesAndCurvesInAnyUnit) {
  const TriMesh a = grooved_plate(1), b = grooved_plate(1000);
  const MultiscaleRidgeValleys ra = multiscale_ridges_valleys(a, {}), rb = multiscale_ridges_valleys(b, {});
  ASSERT_GT(ra.curves.valleys.segments.size(), 50u);
  EXPECT_EQ(ra.curves.valleys.segments.size(), rb.curves.valleys.segments.size());
  EXPECT_EQ(ra.curves.ridges.segments.size(), rb.curves.ridges.segments.size());
  double worst = 0;
  for (int v = 0; v < a.n_vertices(); ++v)
    worst = std::max(worst, std::abs(rb.scale.sigma[v] / 1000 - ra.scale.sigma[v]) / ra.scale.scale.edge);
  std::printf("largest scale difference: %.2e edge lengths\n", worst);
  EXPECT_LT(worst, 1e-3);
}

// One run builds the scan's adjacency, scale and noise once (every scale-space level is the run's
// surface at other positions, and so is the surface the ridges and valleys are drawn on) and
// simulates noise on one patch: the optimal scale's noise floor, the finest reading's (ridges and
// valleys: noise_ridge_strengths) and, for relief edges, the noise tilt at every level share it
// (the scan's noise is above kMinScaleNoise here). The patch's
// adjacency and scale are counted too, and its noise where the tilt is measured; the relief edges'
// smoothed surface keeps its own scale and noise (its lengths are in its own edge lengths). On the
// coin this was 5 adjacencies and 4 scales for ridges and valleys, 13 adjacencies, 12 scales,
// 10 noise estimates and 9 patches for relief edges.
TEST(Multiscale, ARunBuildsTheScansGeometryOnceAndOneNoisePatch) {
  TriMesh m = rktest::height_field([](double x, double) { return 0.05 * std::sin(6 * x); }, 1.0, 50, 0.3, 3);
  rktest::Rng rng(7);
  for (auto& p : m.vertices) p.z() += 0.1 * (2.0 / 50) * rng.normal();  // 10 % of the edge length
  ASSERT_GT(Surface::borrow(m).noise().relative, kMinScaleNoise);
  reset_work_counts();
  multiscale_ridges_valleys(Surface::borrow(m), {});
  WorkCounts c = work_counts();
  EXPECT_EQ(c[Work::NoiseFloor], 1) << c.summary();
  EXPECT_EQ(c[Work::Adjacency], 2) << c.summary();
  EXPECT_EQ(c[Work::MeshScale], 2) << c.summary();
  EXPECT_EQ(c[Work::Noise], 1) << c.summary();
  reset_work_counts();
  multiscale_relief_edges(Surface::borrow(m), {});
  c = work_counts();
  EXPECT_EQ(c[Work::NoiseFloor], 1) << c.summary();
  EXPECT_EQ(c[Work::Adjacency], 2) << c.summary();
  EXPECT_EQ(c[Work::MeshScale], 3) << c.summary();
  EXPECT_EQ(c[Work::Noise], 3) << c.summary();
}

TEST(Multiscale, RefusesMeshesWithoutFacesAndTooSmallForTheScales) {
  TriMesh empty;
  EXPECT_THROW(optimal_scale(empty, {}), InputError);
  TriMesh cloud;
  cloud.vertices = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)};
  EXPECT_THROW(multiscale_ridges_valleys(cloud, {}), InputError);
  // 6 x 6 cells: 8.5 edge lengths across, less than 8 smallest scales of 2 edge lengths.
  const TriMesh tiny = rktest::height_field([](double, double) { return 0.0; }, 1.0, 6);
  OptimalScaleOptions o;
  o.min_scale_edges = 2;
  try {
    optimal_scale(tiny, o);
    ADD_FAILURE() << "a mesh 8 edge lengths across was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("too small"), std::string::npos) << e.what();
  }
  // The same mesh at the smallest scale of 1 edge length fits, with the largest scale lowered.
  const OptimalScale s = optimal_scale(tiny, {});
  EXPECT_TRUE(s.max_scale_lowered);
  EXPECT_LE(s.levels.back(), s.scale.object_size / kMinObjectScales * (1 + 1e-9));
}

// Multi-scale relief edges against the known step line of the noisy disc reliefs on a cylinder
// (a raised and a sunken disc, tanh width 2.5 edge lengths): measured recall / precision
// 1.0000 / 1.0000 at 0, 10 and 20 % noise (asserted: 0.99; it was 0.9, from when 0.96-0.99 was
// measured). The harder case — a sharp small step and a wide soft step on one noisy
// cylinder, multi-scale ahead of every single scale — is not met yet: it is measured by
// bench/bench_multiscale and discussed in docs/multiscale.md.
TEST(Multiscale, ReliefEdgesFollowTheStepsOfNoisyDiscReliefs) {
  for (double noise : {0.0, 0.1, 0.2}) {
    rktest::ReliefShape s;
    s.noise = noise;
    const rktest::Relief r = rktest::discs_on_cylinder(s);
    const MultiscaleReliefEdges ms = multiscale_relief_edges(r.mesh, {});
    const rktest::Detection d = rktest::score(r, ms.curves.edges, r.mean_edge);
    std::printf("noise %.0f %%: recall %.4f precision %.4f\n", 100 * noise, d.recall, d.precision);
    EXPECT_GE(d.recall, 0.99) << noise;
    EXPECT_GE(d.precision, 0.99) << noise;
  }
}

// The relief-edge case: a sharp narrow band (two steps 1.5 edge lengths high and 2.5 apart,
// tanh width 0.3) and a wide soft band (steps 4 high, tanh width 8, 60 apart), three of each,
// on the noisy cylinder. A single scale reads one of them: fine smoothing keeps the narrow band
// apart but leaves the soft step in noise; coarse smoothing merges the narrow band's two steps into
// one bump (its edges then sit at ±σ, off their lines) and still shifts the soft step (on the
// curved cylinder, G crosses zero where it cancels the base's curvature). 20 % noise, and 2 %,
// where nearly every feature is significant and seams between scales were the risk (kReliefFillSmoothness).
TEST(Multiscale, ReliefEdgesOfASharpNarrowBandAndAWideSoftStep) {
  const double h = 2 * M_PI / kAround;
  std::vector<AxialFeature> bands;
  for (int k = 0; k < 6; ++k) {
    const bool sharp = k % 2 == 0;
    bands.push_back({AxialFeature::Band, (k * 300 + 0.37 * k) * h, sharp ? 0.3 * h : 8 * h, sharp ? 1.5 * h : 4 * h,
                     sharp ? 2.5 * h : 60 * h, sharp ? 0 : 1});
  }
  for (double noise : {0.2, 0.02}) {
    const rktest::AxialCylinder cyl = rktest::axial_cylinder(bands, kAround, kBandLength, noise);
    auto evaluate = [&](const char* name, const Polylines& edges) {
      const auto s = rktest::score_axial(cyl, edges, {AxialFeature::Band}, kTolerance, 3 * cyl.edge);
      Score r{name};
      for (size_t i = 0; i < bands.size(); ++i) (bands[i].group == 0 ? r.fine : r.coarse) += s.recall[i] / 3;
      r.precision = s.precision;
      r.f1 = f1(0.5 * (r.fine + r.coarse), r.precision);
      print(r);
      return r;
    };
    std::printf("noise %.0f %% (fine: the narrow band, coarse: the soft one)\n", 100 * noise);
    const MultiscaleReliefEdges ms = multiscale_relief_edges(cyl.mesh, {});
    const Score multi = evaluate("multi-scale", ms.curves.edges);
    // Measured: recall 1.000 / 1.000 at both noise levels, precision 1.000 at 20 % and at 2 % (0.978
    // at 2 % on 72 rows; was asserted 0.95 / 0.95 / 0.8).
    EXPECT_GE(multi.fine, 0.99) << noise;
    EXPECT_GE(multi.coarse, 0.99) << noise;
    EXPECT_GE(multi.precision, noise > 0.1 ? 0.99 : 0.93) << noise;
    if (noise < 0.1) continue;  // with little noise one fine scale reads both (below)
    double best = 0;
    for (double s : {1.0, 1.5, 2.0, 3.0, 4.0, 6.0}) {
      ReliefEdgeParams p;
      p.presmoothing = Length::in_edges(s);
      char name[64];
      std::snprintf(name, sizeof name, "single, %.1f edge lengths", s);
      best = std::max(best, evaluate(name, compute_relief_edges(cyl.mesh, p).edges).f1);
    }
    EXPECT_GE(multi.f1, best + 0.15);
  }
}

// The automatic largest scale (the filters' "auto") is at most 1/32 of a small object's size: on a
// sphere 88 edge lengths across it is lowered to 2.76 (a set largest scale only to 1/8 of it: 11.0).
TEST(Multiscale, AutomaticLargestScaleFollowsTheObjectsSize) {
  const TriMesh ball = rktest::sphere(1.0, 5);
  const MeshScale ms = mesh_scale(ball);
  const double size = ms.object_size / ms.edge;
  for (bool automatic : {true, false}) {
    OptimalScaleOptions o;
    o.max_scale_auto = automatic;
    o.fill = false;
    const OptimalScale s = optimal_scale(ball, o);
    const double expected = std::min(16.0, size / (automatic ? kAutoMaxScaleObjectFraction : kMinObjectScales));
    std::printf("%s: object %.0f edge lengths, largest scale %.2f\n", automatic ? "auto" : "16 set", size,
                s.levels.back() / s.scale.edge);
    EXPECT_NEAR(s.levels.back() / s.scale.edge, expected, 1e-6 * expected);
    EXPECT_TRUE(s.max_scale_lowered);
  }
}

// The normalisation of a curve point's strength (t^γ f, t = σ², as in the scale selection) takes
// the smaller scale of its edge's two ends: where the scale changes across an edge (a fine feature
// beside smooth ground) the larger one would amplify the fine side's curvature by (σ_max / σ_min)^2γ.
// Known answers for an edge from 2 to 6 edge lengths. (The curve tests above cannot tell: on the
// grooved plate at 10 % noise 132 of the 542 valley points lie on edges whose ends' scales differ,
// by up to 1.35 x, yet the max kept the same curves: the grooves' strengths, up to 1.58, are far
// above the threshold, 0.113; at 30 % noise it added 41 points, 4 of them off the grooves.)
TEST(Multiscale, CurveStrengthIsNormalisedAtTheSmallerScaleOfItsEdge) {
  OptimalScale s;
  s.scale.edge = 0.01;
  s.sigma = {0.02, 0.06, 0.06};  // 2, 6 and 6 edge lengths
  Polylines c;
  c.points = {Vec3::Zero(), Vec3::Zero()};
  c.point_edge = {{0, 1}, {1, 2}};
  c.point_weight = {0.8, 0.5};  // near the coarse end: still the fine end's scale
  c.strength = {3.0, 3.0};
  Polylines c2 = c;
  normalise_curve_strengths(c, s, 1.0, 1);   // (σ/h)^2 h
  normalise_curve_strengths(c2, s, 0.5, 2);  // (σ/h) h^2
  std::printf("normalised strengths: %.6g %.6g (gamma 1, power 1), %.6g %.6g (gamma 0.5, power 2)\n", c.strength[0],
              c.strength[1], c2.strength[0], c2.strength[1]);
  EXPECT_NEAR(c.strength[0], 3.0 * 4 * 0.01, 1e-12);  // the larger scale: 3 x 36 x 0.01, 9 x as much
  EXPECT_NEAR(c.strength[1], 3.0 * 36 * 0.01, 1e-12);
  EXPECT_NEAR(c2.strength[0], 3.0 * 2 * 1e-4, 1e-15);
  EXPECT_NEAR(c2.strength[1], 3.0 * 6 * 1e-4, 1e-15);
  // Ridges & valleys are drawn at half the scale here: normalised at the scale the smoothed
  // surface holds, never below its smallest level (1.5 edge lengths).
  s.smoothed_ratio = 0.5;
  s.levels = {0.015, 0.06};
  Polylines c3 = c;
  c3.strength = {3.0, 3.0};
  normalise_curve_strengths(c3, s, 1.0, 1);
  EXPECT_NEAR(c3.strength[0], 3.0 * 1.5 * 1.5 * 0.01, 1e-12);  // 0.5 x 2 = 1 edge length, raised to 1.5
  EXPECT_NEAR(c3.strength[1], 3.0 * 9 * 0.01, 1e-12);          // 0.5 x 6 = 3
}

// How the two readings join: a curve of the other reading within kSameEdgeEdges of one already
// drawn is the same feature (add_other_scale), whatever scale was selected there; the finest
// reading's curves within kFlankReach x its pre-smoothing of the optimal scale's are its blurred
// flanks (drop_blurred_flanks).
TEST(Multiscale, ReadingsJoinWhereEachScaleIsMeant) {
  auto piece = [](double y, int first_vertex) {
    Polylines c;
    for (int i = 0; i <= 10; ++i) {
      c.points.push_back({double(i), y, 0});
      c.strength.push_back(1);
      c.point_edge.push_back({first_vertex + i % 9, first_vertex + i % 9 + 1});
      c.point_weight.push_back(0.5);
    }
    for (int i = 0; i < 10; ++i) c.segments.push_back({i, i + 1}), c.segment_face.push_back(0);
    return c;
  };
  Polylines drawn = piece(0, 0);
  append_curves(drawn, piece(100, 10));
  Polylines other = piece(0.5 * kSameEdgeEdges, 0);  // the same feature
  append_curves(other, piece(40, 0));                // a curve of its own
  Polylines joined = drawn;
  add_other_scale(joined, other, 1.0, 0);
  EXPECT_NEAR(joined.total_length(), 30, 1e-9);  // drawn + the curve of its own
  // The finest reading, pre-smoothing 1 edge length: pieces 1.5 and 3 edge lengths from drawn curves.
  const double presmoothing = 1;
  Polylines finest = piece(1.5, 0);
  append_curves(finest, piece(103, 10));
  drop_blurred_flanks(finest, drawn, presmoothing, 0);
  EXPECT_NEAR(finest.total_length(), 10, 1e-9);  // the nearer piece was a flank
  EXPECT_NEAR(finest.points.front().y(), 103, 1e-12);
}
