// Relief edges (thesis ch. 4), base normals, and ridges & valleys.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <tuple>
#include <cstdio>

#include "reliefkit/demarcating/demarcating.h"
#include "reliefkit/relief_edges/relief_edges.h"
#include "reliefkit/base/cubic_form.h"
#include "reliefkit/base/work_counts.h"
#include "reliefs.h"
#include "reliefkit/relief_edges/ridges.h"
#include "shapes.h"

using namespace reliefkit;

TEST(ReliefEdgeModel, CorrelationMatchesNumericalInnerProduct) {
  // <E1(theta), S1> = integral over phi of E1 * S1 (eq. 4.8), against the closed form (4.13, A).
  CurvatureDerivative C{0.7, -0.3, 0.45, 1.2};
  CurvatureDerivative F = edge_correlation_form(C);
  for (double th : {0.0, 0.4, 1.3, 2.9, -2.0}) {
    double c = std::cos(th), s = std::sin(th), num = 0;
    const int N = 20000;
    for (int k = 0; k < N; ++k) {
      double ph = 2 * M_PI * k / N, cc = std::cos(ph), ss = std::sin(ph);
      double e1 = std::pow(c * cc + s * ss, 3);
      double s1 = C.a * cc * cc * cc + 3 * C.b * cc * cc * ss + 3 * C.c * cc * ss * ss + C.d * ss * ss * ss;
      num += e1 * s1 * 2 * M_PI / N;
    }
    EXPECT_NEAR(F.along(c, s), num, 1e-6) << th;
  }
}

TEST(ReliefEdgeModel, PerfectStepHasZeroFitErrorAndItsDirection) {
  // S1 = alpha (c0 u + s0 v)^3 exactly: the fit recovers theta0, alpha and zero error.
  const double th0 = 0.8, alpha = 2.5, c0 = std::cos(th0), s0 = std::sin(th0);
  CurvatureDerivative C{alpha * c0 * c0 * c0, alpha * c0 * c0 * s0, alpha * c0 * s0 * s0, alpha * s0 * s0 * s0};
  Vec2 m[3];
  int n = cubic_form_maxima(edge_correlation_form(C), m);
  ASSERT_GE(n, 1);
  CubicHarmonics h(edge_correlation_form(C));
  int best = 0;
  for (int i = 1; i < n; ++i)
    if (h.f(m[i].x(), m[i].y()) > h.f(m[best].x(), m[best].y())) best = i;
  EXPECT_NEAR(m[best].x(), c0, 1e-9);
  EXPECT_NEAR(m[best].y(), s0, 1e-9);
  double f = h.f(m[best].x(), m[best].y());
  EXPECT_NEAR(f / (5 * M_PI / 8), alpha, 1e-9);               // eq. 4.14
  EXPECT_NEAR(edge_fit_error(C, 0, 0, f, 1.0), 0.0, 1e-12);  // eq. 4.7 / ||S||^2
  // A pure bowl (curvature, no cubic part) does not resemble a step: error 1.
  EXPECT_NEAR(edge_fit_error({0, 0, 0, 0}, 1, 1, 0, 1.0), 1.0, 1e-12);
}

TEST(BaseNormals, SphereAndCylinderBasesUnderRelief) {
  for (int shape = 0; shape < 2; ++shape) {
    rktest::ReliefShape s;
    s.noise = 0.1;
    rktest::Relief r = shape == 0 ? rktest::disc_on_sphere(s) : rktest::discs_on_cylinder(s);
    Curvature c = compute_curvature(r.mesh);
    BaseNormalOptions o;
    o.scale = default_base_scale(r.mesh);
    BaseNormals b = estimate_base_normals(r.mesh, c.normal, o);
    std::vector<double> err_base, err_surface;
    for (size_t v = 0; v < r.base_normal.size(); ++v) {
      err_base.push_back(std::acos(std::min(1.0, b.normal[v].dot(r.base_normal[v]))) * 180 / M_PI);
      err_surface.push_back(std::acos(std::min(1.0, c.normal[v].dot(r.base_normal[v]))) * 180 / M_PI);
    }
    double mb = rktest::median(err_base), pb = rktest::percentile(err_base, 0.99);
    double ms = rktest::percentile(err_surface, 0.99);
    std::printf("%s: angle to the true base normal: median %.2f, 99th percentile %.2f deg "
                "(surface normals: 99th percentile %.2f deg); %s\n",
                shape == 0 ? "sphere  " : "cylinder", mb, pb, ms, b.solve.summary().c_str());
    EXPECT_TRUE(b.solve.converged);
    // Measured: median 0.07 / 0.22 deg, 99th percentile 7.3 / 7.1 deg (surface normals 29 / 39).
    // Bounds a few times the median and 1.4x the tail: with half the base scale the base follows
    // the relief and the tail grows past them.
    EXPECT_LT(mb, shape == 0 ? 0.25 : 0.7);
    EXPECT_LT(pb, 10.0);
    EXPECT_LT(pb, 0.5 * ms);  // far closer to the base than the surface normals on the relief
  }
}

namespace {
struct CurvedCase {
  const char* name;
  rktest::Relief (*make)(const rktest::ReliefShape&);
};
rktest::Relief sphere_disc(const rktest::ReliefShape& s) { return rktest::disc_on_sphere(s); }
rktest::Relief cylinder_discs(const rktest::ReliefShape& s) { return rktest::discs_on_cylinder(s); }
rktest::Relief cylinder_squares(const rktest::ReliefShape& s) { return rktest::squares_on_cylinder(s); }
const CurvedCase kCurved[] = {
    {"disc on sphere", sphere_disc}, {"discs on cylinder", cylinder_discs}, {"squares on cylinder", cylinder_squares}};
}  // namespace

TEST(ReliefEdgesReliefs, NoiseFree) {
  for (const auto& c : kCurved) {
    rktest::Relief r = c.make({});
    rktest::Detection d = rktest::score(r, compute_relief_edges(r.mesh).edges, r.mean_edge);
    std::printf("%-20s noise-free: relief edges recall %.3f precision %.3f\n", c.name, d.recall, d.precision);
    EXPECT_GE(d.recall, 0.95) << c.name;
    EXPECT_GE(d.precision, 0.90) << c.name;
  }
}

TEST(ReliefEdgesReliefs, NoisyBeatDemarcatingCurves) {
  for (const auto& c : kCurved)
    for (double noise : {0.10, 0.15}) {
      rktest::ReliefShape s;
      s.noise = noise;
      rktest::Relief r = c.make(s);
      // The thesis compares the two at equal pre-smoothing (one edge length); at defaults both
      // smooth as much as the noise asks and both are near perfect (DefaultsOnNoisyReliefs).
      // At one edge length the demarcating curves' strengths are below what the noise alone
      // draws, so their automatic threshold drops them; relief edges still find the reliefs.
      ReliefEdgeParams rp;
      rp.presmoothing = Length::in_edges(1.0);
      DemarcatingParams dp;
      dp.presmoothing = Length::in_edges(1.0);
      rktest::Detection re = rktest::score(r, compute_relief_edges(r.mesh, rp).edges, r.mean_edge);
      rktest::Detection dc = rktest::score(r, compute_demarcating(r.mesh, dp).curves, r.mean_edge);
      std::printf("%-20s noise %.0f%%: relief edges %.3f / %.3f, demarcating curves %.3f / %.3f (recall / precision)\n",
                  c.name, 100 * noise, re.recall, re.precision, dc.recall, dc.precision);
      EXPECT_GE(re.recall, 0.90) << c.name << " " << noise;
      EXPECT_GE(re.precision, 0.85) << c.name << " " << noise;
      // The thesis' claim: better precision at equal or better recall.
      EXPECT_GE(re.recall, dc.recall - 0.01) << c.name << " " << noise;
      EXPECT_GT(re.precision, dc.precision) << c.name << " " << noise;
    }
}

TEST(ReliefEdgesReliefs, DefaultsOnNoisyReliefs) {
  // At defaults (automatic pre-smoothing from the estimated noise) both curve types find the
  // reliefs on curved bases with 10 and 15 % noise.
  for (const auto& c : kCurved)
    for (double noise : {0.10, 0.15}) {
      rktest::ReliefShape s;
      s.noise = noise;
      rktest::Relief r = c.make(s);
      rktest::Detection re = rktest::score(r, compute_relief_edges(r.mesh).edges, r.mean_edge);
      rktest::Detection dc = rktest::score(r, compute_demarcating(r.mesh).curves, r.mean_edge);
      std::printf("%-20s noise %.0f%%, defaults: relief edges %.3f / %.3f, demarcating curves %.3f / %.3f\n", c.name,
                  100 * noise, re.recall, re.precision, dc.recall, dc.precision);
      EXPECT_GE(re.recall, 0.95) << c.name << " " << noise;
      EXPECT_GE(re.precision, 0.90) << c.name << " " << noise;
      EXPECT_GE(dc.recall, 0.95) << c.name << " " << noise;
      EXPECT_GE(dc.precision, 0.85) << c.name << " " << noise;
    }
}

// The reliefs of issue 22's report besides discs, with 15 % noise, at defaults: a ring (a convex
// and a concave outline) and a rounded rectangle on a plane asserted; a five-pointed star printed,
// not asserted. The rectangle's precision was 0.91 while border vertices took cubic jets (false
// edges along the plane's open border; quadratic there: 0.95). The star's 36-degree points are
// narrower than the step's transition over a third of their length: both curve types round them
// off (0.65 / 0.55 here; noise-free without pre-smoothing 0.86 / 0.81, the most any detector of
// this support reaches on it).
TEST(ReliefEdgesReliefs, DefaultsOnRingsAndRoundedRectangles) {
  rktest::ReliefShape s;
  s.noise = 0.15;
  const std::tuple<const char*, rktest::Relief, bool> cases[] = {
      {"ring on sphere", rktest::ring_on_sphere(s), true},
      {"rounded rectangle", rktest::outlines_on_plane(s, false, true), true},
      {"star", rktest::outlines_on_plane(s, true, false), false}};
  for (const auto& [name, r, asserted] : cases) {
    const rktest::Detection re = rktest::score(r, compute_relief_edges(r.mesh).edges, r.mean_edge);
    const rktest::Detection dc = rktest::score(r, compute_demarcating(r.mesh).curves, r.mean_edge);
    std::printf("%-20s noise 15%%, defaults: relief edges %.3f / %.3f, demarcating curves %.3f / %.3f%s\n", name,
                re.recall, re.precision, dc.recall, dc.precision, asserted ? "" : " (not asserted)");
    if (!asserted) continue;
    EXPECT_GE(re.recall, 0.95) << name;
    EXPECT_GE(re.precision, 0.92) << name;
  }
}

// Gaussian grooves and crests on a plane: valley lines along the groove bottoms, ridge lines
// along the crest tops.
namespace {
// Profile z(x) of grooves and crests; its normal curvature across (the surface is invariant
// along y, so the principal curvatures are this and 0): kappa = -z'' / (1 + z'^2)^(3/2) with
// ReliefKit's sign convention. Ridges are its positive maxima, valleys its negative minima.
struct Profile {
  double D = 0.05, sw = 0.05;
  std::vector<double> grooves{-0.5, 0.1}, crests{-0.2, 0.45};
  double z(double x) const {
    double r = 0;
    for (double g : grooves) r -= D * std::exp(-(x - g) * (x - g) / (2 * sw * sw));
    for (double c : crests) r += D * std::exp(-(x - c) * (x - c) / (2 * sw * sw));
    return r;
  }
  double kappa(double x) const {
    const double e = 1e-4;
    double d1 = (z(x + e) - z(x - e)) / (2 * e), d2 = (z(x + e) - 2 * z(x) + z(x - e)) / (e * e);
    return -d2 / std::pow(1 + d1 * d1, 1.5);
  }
  std::vector<double> extrema(bool valleys) const {
    std::vector<double> out;
    const double h = 1e-4;
    for (double x = -0.95; x < 0.95; x += h) {
      double a = kappa(x - h), b = kappa(x), c = kappa(x + h);
      if (!valleys && b > a && b >= c && b > 1.0) out.push_back(x);
      if (valleys && b < a && b <= c && b < -1.0) out.push_back(x);
    }
    return out;
  }
};
}  // namespace

TEST(RidgesValleys, GroovesAndCrests) {
  Profile pr;
  for (double noise : {0.0, 0.1}) {
    TriMesh m = rktest::height_field([&](double x, double) { return pr.z(x); }, 1.0, 150, 0.3, 4);
    double h = edge_length_stats(m).mean;
    rktest::Rng rng(17);
    for (auto& p : m.vertices) p.z() += noise * h * rng.normal();
    RidgeValleyResult r = compute_ridges_valleys(m);
    for (bool valleys : {true, false}) {
      const Polylines& p = valleys ? r.valleys : r.ridges;
      std::vector<double> lines = pr.extrema(valleys);
      ASSERT_EQ(lines.size(), 6u);  // 2 bottoms/tops + 4 feet/shoulders of the other kind
      double near = 0, total = 0, inner = 0;
      for (const auto& s : p.segments) {
        Vec3 mid = 0.5 * (p.points[s[0]] + p.points[s[1]]);
        double len = (p.points[s[0]] - p.points[s[1]]).norm(), d = 1e9;
        for (double x : lines) d = std::min(d, std::abs(mid.x() - x));
        total += len;
        if (d <= h) near += len;
        if (std::abs(mid.y()) < 0.9) inner += len;
      }
      const char* what = valleys ? "valleys" : "ridges";
      std::printf("%s, noise %.0f%%: %.3f of the curve length within one edge length of the true lines; "
                  "length %.2f along |y| < 0.9 (true: %.1f)\n",
                  what, 100 * noise, total > 0 ? near / total : 0.0, inner, 6 * 1.8);
      // Third-order quantities are noise-sensitive: short spurious ridges survive 10 % noise.
      EXPECT_GE(near / total, noise > 0 ? 0.85 : 0.95) << what;
      EXPECT_GT(inner, 0.9 * 6 * 1.8) << what;
    }
  }
}

// Noise alone, on a featureless plane at defaults, draws next to no lines: the thresholds stay above what
// the same pre-smoothing and selection draw on a noise patch (noise_ridge_strengths). Without
// that floor (the median |k| and the strongest segments' percentile alone) the noise drew 2,200
// edge lengths of ridges and valleys at 20 % noise.
TEST(RidgesValleys, NoiseAloneDrawsNoLinesAtDefaults) {
  for (double noise : {0.2, 0.3}) {
    TriMesh m = rktest::height_field([](double, double) { return 0.0; }, 1.0, 150, 0.3, 5);
    const double h = edge_length_stats(m).mean;
    rktest::Rng rng(23);
    for (auto& p : m.vertices) p.z() += noise * h * rng.normal();
    const RidgeValleyResult r = compute_ridges_valleys(m);
    double length = 0;
    for (const Polylines* p : {&r.ridges, &r.valleys})
      for (const auto& s : p->segments) length += (p->points[s[0]] - p->points[s[1]]).norm();
    const double per_kface = length / h / (m.n_faces() / 1000.0);
    std::printf("noise %.0f%%, pre-smoothing %.2f edge lengths: lines %.1f edge lengths long (%.2f per 1,000 faces)\n",
                100 * noise, r.presmoothing / h, length / h, per_kface);
    // Measured: 0 at 20 %, one line of 12.6 edge lengths at 30 % (0.28 per 1,000 faces; the quietest
    // real scan's layer carries 3-5, a coin's 20-35: docs/curve-layers.md).
    EXPECT_LT(per_kface, 1.0) << noise;
  }
}

// The per-vertex fields on their own: what compute_relief_edges computes before its curves,
// without the noise-floor simulation (it serves the curves' thresholds alone); the crossings of G
// give the detector's own thresholds, and the steep ones lie on the disc's true rim.
TEST(ReliefEdgeFields, TheDetectorsOwnFieldsWithoutItsCurves) {
  rktest::ReliefShape shape;
  shape.noise = 0.1;
  const rktest::Relief r = rktest::disc_on_plane(shape, 80);
  const Surface surface = Surface::borrow(r.mesh);
  reset_work_counts();
  const ReliefEdgeFields f = compute_relief_edge_fields(surface);
  EXPECT_EQ(work_counts()[Work::NoiseFloor], 0) << work_counts().summary();
  const ReliefEdgeResult e = compute_relief_edges(surface);
  EXPECT_EQ(work_counts()[Work::NoiseFloor], 1) << work_counts().summary();
  EXPECT_EQ(f.G, e.G);
  EXPECT_EQ(f.direction, e.direction);
  EXPECT_EQ(f.fit_error, e.fit_error);
  EXPECT_EQ(f.angle, e.angle);
  EXPECT_EQ(f.base.normal, e.base.normal);
  EXPECT_EQ(f.window, e.window);
  const Polylines crossings = relief_edge_crossings(surface, f);
  const ReliefEdgeThresholds t = relief_edge_thresholds(surface, f, crossings);
  EXPECT_EQ(t.strong_angle, e.strong_angle);
  EXPECT_EQ(t.weak_angle, e.weak_angle);
  EXPECT_EQ(t.noise_angle, e.noise_angle);
  EXPECT_EQ(e.weak_angle, 0.5 * e.strong_angle);  // automatic: half the strong tilt
  // Strong points (the hysteresis' seeds: steep and fitting the step model) lie on the rim.
  const std::vector<double> error = interpolate_at_points(crossings, f.fit_error);
  double on_rim = 0, steep = 0;
  for (size_t i = 0; i < crossings.points.size(); ++i) {
    if (crossings.strength[i] < e.strong_angle || error[i] > ReliefEdgeParams().strong_error) continue;
    const Vec3& x = crossings.points[i];
    steep += 1;
    on_rim += std::abs(std::hypot(x.x(), x.y()) - 0.5) <= 2 * r.mean_edge;
  }
  std::printf("strong crossing points: %.0f, %.3f of them within 2 edge lengths of the rim\n", steep, on_rim / steep);
  ASSERT_GT(steep, 100);
  EXPECT_GE(on_rim / steep, 0.95);
}

// The hysteresis steepness and the orientation restriction's least tilt are separate settings.
TEST(ReliefEdgeParams, WeakSteepnessAndRestrictionTiltAreSeparateSettings) {
  rktest::ReliefShape shape;
  shape.noise = 0.1;
  const rktest::Relief r = rktest::disc_on_plane(shape, 80);
  const Surface surface = Surface::borrow(r.mesh);
  ReliefEdgeParams p;
  p.strong_angle = 0.1, p.weak_angle = 0.03;
  const ReliefEdgeResult e = compute_relief_edges(surface, p);
  EXPECT_EQ(e.strong_angle, 0.1);
  EXPECT_EQ(e.weak_angle, 0.03);
  // No vertex tilts more than 90 degrees: that least tilt restricts none, as no restriction.
  ReliefEdgeParams none, off;
  none.restriction_min_tilt = 3.14159265358979323846 / 2;
  off.restrict_orientation = false;
  const ReliefEdgeFields f_none = compute_relief_edge_fields(surface, none);
  const ReliefEdgeFields f_off = compute_relief_edge_fields(surface, off);
  EXPECT_EQ(f_none.direction, f_off.direction);
  EXPECT_NE(e.direction, f_off.direction);  // the default 11 degrees restricts the rim's vertices
  none.restriction_min_tilt = 2;
  EXPECT_THROW(compute_relief_edge_fields(surface, none), InputError);
}

// What another stage supplies: given base normals replace the estimate (no Laplacian is built);
// a given base shape operator S is taken off G: G - G_given = t^T S t along the edge direction t,
// which for a sphere's (I - z z^T) / R over the plane is (1 - t_z^2) / R.
TEST(ReliefEdgeGuidance, GivenBaseReplacesTheEstimateAndWrongSizesAreRefused) {
  const rktest::Relief r = rktest::disc_on_plane({}, 80);
  const Surface surface = Surface::borrow(r.mesh);
  const size_t nv = r.mesh.vertices.size();
  ReliefEdgeParams p;
  p.edge_smoothing = Length::in_edges(0);  // G as the edge model gives it
  const ReliefEdgeFields plain = compute_relief_edge_fields(surface, p);
  ReliefEdgeGuidance given;
  given.base_normals = r.base_normal;
  reset_work_counts();
  const ReliefEdgeFields with_normals = compute_relief_edge_fields(Surface::borrow(r.mesh), p, given);
  EXPECT_EQ(work_counts()[Work::Laplacian], 0) << work_counts().summary();
  EXPECT_EQ(with_normals.base.normal, r.base_normal);
  ReliefEdgeGuidance shaped;
  const double radius = 3;
  shaped.base_shape.assign(nv, (Mat3::Identity() - Vec3::UnitZ() * Vec3::UnitZ().transpose()) / radius);
  const ReliefEdgeFields with_shape = compute_relief_edge_fields(surface, p, shaped);
  ASSERT_EQ(with_shape.direction, plain.direction);
  double worst = 0;
  for (size_t v = 0; v < nv; ++v) {
    const double tz = plain.direction[v].z();
    worst = std::max(worst, std::abs(plain.G[v] - with_shape.G[v] - (1 - tz * tz) / radius));
  }
  EXPECT_LT(worst, 1e-9);
  ReliefEdgeGuidance wrong;
  wrong.noise_tilt.assign(nv - 1, 0.1);
  EXPECT_THROW(compute_relief_edge_fields(surface, p, wrong), std::invalid_argument);
  EXPECT_THROW(relief_edge_crossings(surface, plain, wrong), std::invalid_argument);
}

// The multi-scale filter's connecting rules for ridge lines (select_lines): a line that
// weakens to 0.6 of the threshold for a few segments, and a second piece across a gap of 3.
TEST(RidgesValleys, WeakStretchesAndSmallGapsJoinTheLines) {
  Polylines all;
  auto line = [&all](double x0, int n, std::vector<int> weak_points) {
    const int base = static_cast<int>(all.points.size());
    for (int i = 0; i <= n; ++i) {
      all.points.push_back({x0 + i, 0, 0});
      all.strength.push_back(std::count(weak_points.begin(), weak_points.end(), i) ? 0.6 : 1.0);
    }
    for (int i = 0; i < n; ++i) all.segments.push_back({base + i, base + i + 1}), all.segment_face.push_back(0);
  };
  line(0, 20, {9, 10, 11});
  line(23, 10, {});
  const LineLinking thresholds_only;  // weak_ratio 1, no gap bridging: the line breaks at 8 and 8
  EXPECT_NEAR(select_lines(all, 1.0, thresholds_only, 1.0, 9.0).total_length(), 10.0, 1e-9);
  LineLinking connecting;
  connecting.weak_ratio = 0.5;
  const Polylines joined = select_lines(all, 1.0, connecting, 1.0, 9.0);
  EXPECT_NEAR(joined.total_length(), 30.0, 1e-9);
  EXPECT_EQ(joined.chains().size(), 2u);
  connecting.gap_edges = 4;
  const Polylines bridged = select_lines(all, 1.0, connecting, 1.0, 9.0);
  EXPECT_NEAR(bridged.total_length(), 33.0, 1e-9);
  EXPECT_EQ(bridged.chains().size(), 1u);
}
