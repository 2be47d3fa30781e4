// "Unroll Around Axis" (reliefkit/rollout/unroll.h) on pieces of known geometry
// (tests/support/turned.h): an embossed cylinder, a cone with a carved band, a globular band; the
// bars are issue 43's.
#include <gtest/gtest.h>

#include <cmath>

#include "reliefkit/base/scale.h"
#include "reliefkit/rollout/unroll.h"
#include "shapes.h"
#include "turned.h"

using namespace reliefkit;
using rktest::TurnedOptions;
using rktest::TurnedShape;

namespace {

// Each face edge's length on the rollout against the input's, as a change (0.01 = 1 %).
std::vector<double> edge_changes(const TriMesh& input, const Rollout& r) {
  const int n = input.n_vertices();
  auto original = [&](int v) { return v < n ? v : r.copy_of[size_t(v - n)]; };
  std::vector<double> change;
  for (const auto& t : r.mesh.faces)
    for (int k = 0; k < 3; ++k) {
      const int a = t[size_t(k)], b = t[size_t((k + 1) % 3)];
      const double before = (input.vertices[size_t(original(a))] - input.vertices[size_t(original(b))]).norm();
      if (before > 0) change.push_back(std::abs((r.mesh.vertices[size_t(a)] - r.mesh.vertices[size_t(b)]).norm() / before - 1));
    }
  return change;
}

// The least-squares slope of the rollout's heights against the true relief (through their means).
double height_slope(const rktest::Turned& t, const Rollout& r) {
  double mx = 0, my = 0;
  const size_t n = t.relief.size();
  for (size_t i = 0; i < n; ++i) mx += t.relief[i] / n, my += r.height[i] / n;
  double sxy = 0, sxx = 0;
  for (size_t i = 0; i < n; ++i) sxy += (t.relief[i] - mx) * (r.height[i] - my), sxx += (t.relief[i] - mx) * (t.relief[i] - mx);
  return sxy / sxx;
}

}  // namespace

TEST(Unroll, EmbossedCylinderKeepsLengthsWidthAndHeights) {
  TurnedOptions o;
  o.irregular = true, o.seed = 3;
  const rktest::Turned t = rktest::make_turned(o);
  const Rollout r = unroll(Surface(t.mesh));
  ASSERT_TRUE(r.fit.has_value());
  EXPECT_GT(std::abs(r.map->axis().direction.dot(t.axis_direction)), std::cos(0.2 * M_PI / 180));
  EXPECT_NEAR(r.width, 2 * M_PI * o.radius, 0.01 * 2 * M_PI * o.radius);
  const std::vector<double> change = edge_changes(t.mesh, r);
  EXPECT_LT(percentile(change, 0.5), 0.005);
  EXPECT_LT(percentile(change, 0.9), 0.02);
  const double slope = height_slope(t, r);
  EXPECT_GT(slope, 0.97);
  EXPECT_LT(slope, 1.03);
  EXPECT_LT(r.stretch_p90, 0.005);  // a cylinder develops without stretch
  // One sheet: the seam's faces were moved to one side, none spans the sheet.
  for (const auto& f : r.mesh.faces)
    for (int k = 0; k < 3; ++k)
      ASSERT_LT((r.mesh.vertices[size_t(f[size_t(k)])] - r.mesh.vertices[size_t(f[size_t((k + 1) % 3)])]).norm(), 5 * o.edge);
}

TEST(Unroll, ConeWithACarvedBandDevelopsWithoutStretch) {
  TurnedOptions o;
  o.shape = TurnedShape::cone, o.band = true, o.relief = -0.4, o.seed = 5;
  const rktest::Turned t = rktest::make_turned(o);
  UnrollParams p;
  p.base = BaseShape::straight;
  const Rollout r = unroll(Surface(t.mesh), p);
  EXPECT_LT(r.stretch_p90, 0.005);
  const std::vector<double> change = edge_changes(t.mesh, r);
  EXPECT_LT(percentile(change, 0.5), 0.005);
  const double slope = height_slope(t, r);
  EXPECT_GT(slope, 0.97);
  EXPECT_LT(slope, 1.03);
  // The smooth base keeps the band as relief too (a band narrower than half its window).
  const Rollout smooth = unroll(Surface(t.mesh));
  EXPECT_GT(height_slope(t, smooth), 0.9);
}

TEST(Unroll, GlobularBandReportsTheStretchItHas) {
  TurnedOptions o;
  o.shape = TurnedShape::globe, o.radius = 20, o.length = 24, o.relief = 0, o.seed = 2;
  const rktest::Turned t = rktest::make_turned(o);
  const Rollout r = unroll(Surface(t.mesh));
  const std::vector<double> change = edge_changes(t.mesh, r);
  const double measured_median = percentile(change, 0.5), measured_p90 = percentile(change, 0.9);
  EXPECT_GT(measured_p90, 0.01);  // a sphere's band cannot develop without stretch
  EXPECT_NEAR(r.stretch_median, measured_median, 0.25 * measured_median + 0.002);
  EXPECT_NEAR(r.stretch_p90, measured_p90, 0.25 * measured_p90 + 0.002);
}

TEST(Unroll, SealImpressionIsTheRolloutMirroredWithItsReliefInverted) {
  TurnedOptions o;
  o.seed = 7;
  const rktest::Turned t = rktest::make_turned(o);
  UnrollParams p;
  p.seam_deg = 30;
  const Rollout r = unroll(Surface(t.mesh), p);
  p.impression = true;
  const Rollout seal = unroll(Surface(t.mesh), p);
  ASSERT_EQ(r.mesh.vertices.size(), seal.mesh.vertices.size());
  // Both face the viewer (+Z) as the seal's surface faced outwards: the mirror turns faces back.
  for (const Rollout* x : {&r, &seal}) {
    Vec3 normal = Vec3::Zero();
    for (const auto& f : x->mesh.faces)
      normal += (x->mesh.vertices[size_t(f[1])] - x->mesh.vertices[size_t(f[0])]).cross(x->mesh.vertices[size_t(f[2])] - x->mesh.vertices[size_t(f[0])]);
    EXPECT_GT(normal.normalized().z(), 0.99);
  }
  for (size_t i = 0; i < r.mesh.vertices.size(); ++i) {
    EXPECT_NEAR(seal.height[i], -r.height[i], 1e-9);
    EXPECT_NEAR(seal.mesh.vertices[i].x(), -r.mesh.vertices[i].x(), 1e-9);
    EXPECT_NEAR(seal.mesh.vertices[i].y(), r.mesh.vertices[i].y(), 1e-9);
  }
}

TEST(Unroll, CurvesOnTheRolloutAreTheRolloutOfTheCurves) {
  TurnedOptions o;
  o.seed = 4;
  const rktest::Turned t = rktest::make_turned(o);
  const Rollout r = unroll(Surface(t.mesh));
  // A curve across the seam and round the piece: the plane cut square to the axis at its middle.
  const Vec3 d = r.map->axis().direction;
  const Vec3 middle = t.axis_point + 0.0 * d;
  const Polylines ring = plane_cut(t.mesh, d, middle.dot(d) + 0.37);
  ASSERT_GT(ring.segments.size(), 100u);
  const Polylines unrolled = unroll_curves(ring, *r.map);
  // Its points lie on the rollout's surface where the cut's edges lie: each unrolled point between
  // the rollout's images of its edge's ends (the map is smooth within an edge).
  for (size_t k = 0; k < ring.points.size(); ++k) {
    const auto [a, b] = ring.point_edge[k];
    const double w = ring.point_weight[k];
    const RolloutMap::Point pa = r.map->map(t.mesh.vertices[size_t(a)]), pb = r.map->map(t.mesh.vertices[size_t(b)]);
    if (std::abs(pa.angle - pb.angle) > M_PI) continue;  // an edge across the seam
    EXPECT_LT((unrolled.points[k] - ((1 - w) * pa.position + w * pb.position)).norm(), 0.05 * o.edge);
  }
  // The ring is one line across the sheet: its length is the circumference at its radius, cut at the seam.
  EXPECT_NEAR(unrolled.total_length(), ring.total_length(), 0.01 * ring.total_length());
  double low = INFINITY, high = -INFINITY;
  for (const Vec3& q : unrolled.points) low = std::min(low, q.x()), high = std::max(high, q.x());
  EXPECT_NEAR(high - low, r.width, 0.02 * r.width);
}

TEST(Unroll, RefusesWhatTurnsAboutNoAxis) {
  EXPECT_THROW(unroll(Surface(rktest::sphere(10, 4))), InputError);
  TriMesh plane = rktest::height_field([](double, double) { return 0.0; }, 10, 40);
  EXPECT_THROW(unroll(Surface(plane)), InputError);
  TriMesh cloud;
  cloud.vertices = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)};
  EXPECT_THROW(unroll(Surface(cloud)), InputError);
  // A piece the vessel fit lets through but that does not turn about its axis (a cylinder whose
  // figures stand out as far as its radius): refused with the figure, as the scans' coin and ingot are.
  TurnedOptions lumpy;
  lumpy.relief = 15;
  try {
    unroll(Surface(rktest::make_turned(lumpy).mesh));
    ADD_FAILURE() << "a lumpy cylinder was unrolled about a fitted axis";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("does not turn about the fitted axis"), std::string::npos) << e.what();
  }
  UnrollParams bad;
  bad.axis_source = AxisSource::given, bad.given_axis.direction = Vec3::Zero();
  EXPECT_THROW(unroll(Surface(rktest::make_turned({}).mesh), bad), InputError);
}
