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
  auto original = [&](int v) { return r.source[size_t(v)]; };
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
  const Vec3 d = r.map->axis().direction;  // pointing up the screen as MeshLab shows the scan (+y)
  if (std::abs(d.y()) >= 0.1) EXPECT_GT(d.y(), 0);
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

// Each face's angles on the rollout against the input's: the largest change per face (degrees).
std::vector<double> angle_changes(const TriMesh& input, const Rollout& r) {
  const int n = input.n_vertices();
  auto original = [&](int v) { return r.source[size_t(v)]; };
  auto angle_at = [](const Vec3& a, const Vec3& b, const Vec3& c) { return std::acos(std::clamp((b - a).normalized().dot((c - a).normalized()), -1.0, 1.0)); };
  std::vector<double> change;
  for (const auto& t : r.mesh.faces) {
    double worst = 0;
    for (int k = 0; k < 3; ++k) {
      const int a = t[size_t(k)], b = t[size_t((k + 1) % 3)], c = t[size_t((k + 2) % 3)];
      const double before = angle_at(input.vertices[size_t(original(a))], input.vertices[size_t(original(b))], input.vertices[size_t(original(c))]);
      const Vec3 flat_a(r.mesh.vertices[size_t(a)].x(), r.mesh.vertices[size_t(a)].y(), 0), flat_b(r.mesh.vertices[size_t(b)].x(), r.mesh.vertices[size_t(b)].y(), 0),
          flat_c(r.mesh.vertices[size_t(c)].x(), r.mesh.vertices[size_t(c)].y(), 0);
      worst = std::max(worst, std::abs(angle_at(flat_a, flat_b, flat_c) - before) * 180 / M_PI);
    }
    change.push_back(worst);
  }
  return change;
}

TEST(Unroll, GlobularBandReportsTheStretchItHasAndConformalKeepsShapes) {
  TurnedOptions o;
  o.shape = TurnedShape::globe, o.radius = 20, o.length = 24, o.relief = 0, o.seed = 2;
  const rktest::Turned t = rktest::make_turned(o);
  for (Development d : {Development::conformal, Development::equal_area}) {
    SCOPED_TRACE(int(d));
    UnrollParams p;
    p.development = d;
    const Rollout r = unroll(Surface(t.mesh), p);
    const std::vector<double> change = edge_changes(t.mesh, r);
    const double measured_median = percentile(change, 0.5), measured_p90 = percentile(change, 0.9);
    EXPECT_GT(measured_p90, 0.01);  // a sphere's band cannot develop without stretch
    EXPECT_NEAR(r.stretch_median, measured_median, 0.25 * measured_median + 0.002);
    EXPECT_NEAR(r.stretch_p90, measured_p90, 0.25 * measured_p90 + 0.002);
    const std::vector<double> turn = angle_changes(t.mesh, r);
    std::printf("%s: stretch median %.2f %%, p90 %.2f %%; angle change median %.3f, p90 %.3f degrees\n",
                d == Development::conformal ? "conformal" : "equal-area", 100 * measured_median, 100 * measured_p90,
                percentile(turn, 0.5), percentile(turn, 0.9));
    if (d == Development::conformal) {
      EXPECT_LT(percentile(turn, 0.9), 1.0);  // shapes kept: the faces' angles within the map's curvature over a face
    } else {
      EXPECT_GT(percentile(turn, 0.9), 5.0);  // sheared away from the middle meridian
    }
  }
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

TEST(Unroll, RepeatPastTheSeamContinuesTheSheetByTheShareAsked) {
  TurnedOptions o;
  o.seed = 6;
  const rktest::Turned t = rktest::make_turned(o);
  UnrollParams p;
  p.base = BaseShape::straight;
  p.seam_deg = 50;
  const Rollout plain = unroll(Surface(t.mesh), p);
  p.repeat_share = 0.25;
  const Rollout repeated = unroll(Surface(t.mesh), p);
  auto width = [](const TriMesh& m) {
    double low = INFINITY, high = -INFINITY;
    for (const Vec3& q : m.vertices) low = std::min(low, q.x()), high = std::max(high, q.x());
    return high - low;
  };
  EXPECT_NEAR(width(plain.mesh), plain.width, 0.01 * plain.width);
  EXPECT_NEAR(width(repeated.mesh), 1.25 * plain.width, 0.01 * plain.width);
  EXPECT_NEAR(double(repeated.repeated_faces), 0.25 * double(plain.mesh.faces.size()), 0.03 * double(plain.mesh.faces.size()));
  // Each repeated face is an input face one turn on (its points mapped a turn on; about a
  // circumference along the sheet: the fitted base is a cone of slope ~1e-4), with its heights.
  const size_t faces = repeated.mesh.faces.size() - size_t(repeated.repeated_faces), n = t.mesh.vertices.size();
  for (size_t f = faces; f < repeated.mesh.faces.size(); ++f)
    for (int v : repeated.mesh.faces[f]) {
      ASSERT_GE(size_t(v), n);
      const size_t original = size_t(repeated.source[size_t(v)]);
      const Vec3 shift = repeated.mesh.vertices[size_t(v)] - repeated.mesh.vertices[original];
      EXPECT_LT((repeated.mesh.vertices[size_t(v)] - repeated.map->map(t.mesh.vertices[original], 1).position).norm(), 1e-9);
      EXPECT_NEAR(shift.x(), repeated.width, 1e-3 * repeated.width);
      EXPECT_NEAR(shift.y(), 0, 1e-3 * repeated.width);
      EXPECT_NEAR(repeated.height[size_t(v)], repeated.height[original], 1e-12);
    }
  // The stretch counts each face once; the input's vertices keep their places.
  EXPECT_NEAR(repeated.stretch_p90, plain.stretch_p90, 1e-9);
  for (size_t i = 0; i < n; ++i) ASSERT_EQ(repeated.mesh.vertices[i], plain.mesh.vertices[i]);
  // The seam's lines: the sheet's two edges, a circumference apart on a cylinder.
  ASSERT_EQ(repeated.marks.seams.size(), 2u);
  for (size_t k = 0; k < repeated.marks.seams[0].size(); ++k)
    EXPECT_NEAR(repeated.marks.seams[1][k].x() - repeated.marks.seams[0][k].x(), repeated.width, 1e-3 * repeated.width);
  EXPECT_EQ(sheet_labels(repeated.marks, 1).size(), 3u);
  EXPECT_NE(sheet_labels(repeated.marks, 1)[2].find("25 % of a turn"), std::string::npos);
  // The curves repeat with the faces: the middle ring one and a quarter times round.
  const Vec3 d = repeated.map->axis().direction;
  const Polylines ring = plane_cut(t.mesh, d, t.axis_point.dot(d) + 0.37);
  const Polylines once = unroll_curves(ring, *repeated.map), again = unroll_curves(ring, *repeated.map, 0.25);
  EXPECT_NEAR(again.total_length(), 1.25 * once.total_length(), 0.02 * once.total_length());
  EXPECT_THROW(unroll(Surface(t.mesh), [] { UnrollParams q; q.repeat_share = 1.5; return q; }()), InputError);
}

// A cylinder seal as it is scanned: closed at both ends and pierced by a bore. Only the outer
// wall is unrolled; the ends and the bore are left out (and said), the rest as for the open tube.
TEST(Unroll, AClosedPiercedSealUnrollsItsOuterWallOnly) {
  TurnedOptions o;
  o.closed = true, o.irregular = true, o.seed = 8, o.relief = -0.5, o.frieze = true;  // carved, as seals are
  const rktest::Turned t = rktest::make_turned(o);
  ASSERT_GT(t.mesh.n_faces(), t.wall_faces + 1000);
  const Rollout r = unroll(Surface(t.mesh));
  EXPECT_EQ(r.left_out_faces, t.mesh.n_faces() - t.wall_faces);
  EXPECT_EQ(r.mesh.n_faces(), t.wall_faces);
  double ends_and_bore = 0, total = 0;  // the generator's faces after the wall's
  for (int f = 0; f < t.mesh.n_faces(); ++f) {
    const auto& v = t.mesh.faces[size_t(f)];
    const double area = (t.mesh.vertices[size_t(v[1])] - t.mesh.vertices[size_t(v[0])]).cross(t.mesh.vertices[size_t(v[2])] - t.mesh.vertices[size_t(v[0])]).norm();
    total += area, ends_and_bore += f >= t.wall_faces ? area : 0;
  }
  EXPECT_NEAR(r.left_out_area_share, ends_and_bore / total, 1e-9);
  EXPECT_NEAR(r.width, 2 * M_PI * o.radius, 0.01 * 2 * M_PI * o.radius);
  double mx = 0, my = 0, sxy = 0, sxx = 0;
  const double n = double(r.wall_vertices);
  for (long i = 0; i < r.wall_vertices; ++i) {
    const double truth = t.relief[size_t(r.source[size_t(i)])];
    ASSERT_TRUE(std::isfinite(truth));  // a wall vertex
    mx += truth / n, my += r.height[size_t(i)] / n;
  }
  for (long i = 0; i < r.wall_vertices; ++i) {
    const double truth = t.relief[size_t(r.source[size_t(i)])];
    sxy += (truth - mx) * (r.height[size_t(i)] - my), sxx += (truth - mx) * (truth - mx);
  }
  EXPECT_NEAR(sxy / sxx, 1.0, 0.03);
  const std::vector<double> change = edge_changes(t.mesh, r);
  EXPECT_LT(percentile(change, 0.5), 0.005);
  EXPECT_LT(percentile(change, 0.9), 0.02);
  // The input's vertices in their order: the sources of the wall's vertices increase.
  for (long i = 1; i < r.wall_vertices; ++i) ASSERT_LT(r.source[size_t(i - 1)], r.source[size_t(i)]);
  std::string log;
  for (const std::string& line : rollout_log_lines(r)) log += line + "\n";
  char said[80];
  std::snprintf(said, sizeof said, "Left out: %ld faces (%.1f %%", r.left_out_faces, 100 * ends_and_bore / total);
  EXPECT_NE(log.find(said), std::string::npos) << log;
}
