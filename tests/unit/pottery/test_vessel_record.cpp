// "Vessel Axis and Profile" (reliefkit/pottery/vessel_record.h) on synthetic vessels and sherds of
// known axis and profile (tests/support/sherds.h). The bars are issue 42's (axis 0.5 degrees,
// offset 1 % of the radius, profile median 0.5 % / 90th percentile 1.5 % of the largest radius);
// where the method does better the tolerance is a few times what bench_pottery measured.
#include <gtest/gtest.h>

#include <cmath>

#include "reliefkit/drawing/vessel_profile.h"
#include "shapes.h"
#include "sherds.h"
#include "vessels.h"

using namespace reliefkit;
using rktest::SherdOptions;
using rktest::VesselShape;

namespace {

SherdOptions options(VesselShape shape, double span, double from, double to, double noise, unsigned seed = 1) {
  SherdOptions o;
  o.shape = shape, o.span_deg = span, o.from = from, o.to = to, o.noise = noise, o.irregular = true, o.seed = seed;
  return o;
}

struct PotteryRun {
  rktest::Sherd sherd;
  VesselRecord record;
  rktest::SherdScore score;
};
PotteryRun run(const SherdOptions& o) {
  PotteryRun r{rktest::make_sherd(o), {}, {}};
  r.record = record_vessel(Surface(r.sherd.mesh));
  r.score = rktest::score_record(r.sherd, r.record);
  return r;
}

}  // namespace

TEST(VesselRecord, WholeJarOnItsBase) {
  SherdOptions o = options(VesselShape::jar, 360, 0, 1, 0.05);
  o.irregular = false;
  const PotteryRun r = run(o);
  EXPECT_LT(r.score.angle_deg, 0.02);   // measured 0.001
  EXPECT_LT(r.score.offset, 0.0005);    // 0.00001
  EXPECT_LT(r.score.profile_median, 0.002);  // 0.0006
  EXPECT_LT(r.score.profile_p90, 0.005);     // 0.0014
  EXPECT_TRUE(r.score.up_right);
  EXPECT_EQ(r.record.up_rule, UpRule::base);
  ASSERT_TRUE(r.record.has_rim);
  EXPECT_LT(r.score.rim_diameter, 0.005);
  EXPECT_NEAR(r.record.rim_share, 1.0, 0.01);
  EXPECT_NEAR(r.record.thickness_low, 5, 0.5);
  EXPECT_NEAR(r.record.thickness_high, 5, 0.5);
  // the pose: axis +Z through the origin, lowest point at z = 0, vertices in their order
  const TriMesh moved = oriented_mesh(r.sherd.mesh, r.record);
  ASSERT_EQ(moved.vertices.size(), r.sherd.mesh.vertices.size());
  double z_min = INFINITY;
  for (const Vec3& p : moved.vertices) z_min = std::min(z_min, p.z());
  EXPECT_NEAR(z_min, 0, 1e-9);
  const Vec3 up = r.record.rotation * r.sherd.axis_direction;
  EXPECT_GT(up.z(), std::cos(0.02 * M_PI / 180));
}

TEST(VesselRecord, RimSherdsOfAThirdAndAFifth) {
  for (const auto& o : {options(VesselShape::jar, 108, 0.7, 1, 0.1), options(VesselShape::bowl, 72, 0.5, 1, 0.1)}) {
    const PotteryRun r = run(o);
    SCOPED_TRACE(o.span_deg);
    EXPECT_LT(r.score.angle_deg, 0.5);  // measured 0.12, 0.22
    EXPECT_LT(r.score.offset, 0.01);    // 0.13 %, 0.37 %
    EXPECT_LT(r.score.profile_median, 0.005);  // 0.11 %, 0.18 %
    EXPECT_LT(r.score.profile_p90, 0.015);     // 0.25 %, 0.43 %
    EXPECT_GT(r.score.sides_right, 0.95);      // outer and inner wall told apart
    EXPECT_TRUE(r.score.up_right);
    EXPECT_EQ(r.record.up_rule, UpRule::rim);
    ASSERT_TRUE(r.record.has_rim);
    EXPECT_LT(r.score.rim_diameter, 0.01);  // 0.13 %, 0.08 %
    EXPECT_NEAR(r.record.rim_share, o.span_deg / 360, 0.02);
    // the stated uncertainties cover the true errors
    EXPECT_LT(r.score.angle_deg, 3 * r.record.angle_uncertainty_deg + 0.05);
    EXPECT_LT(r.score.rim_diameter * r.sherd.rim_diameter, 3 * r.record.diameter_uncertainty);
  }
}

// A tenth of the rim: the tilt in the plane through the sherd's middle is held only by how the
// wall curves across 36 degrees. Seed 4 leaned 3.1 degrees while the rounded rim's fold counted
// in the profile's thinness.
TEST(VesselRecord, RimSherdOfATenth) {
  for (unsigned seed : {1u, 4u}) {
    const PotteryRun r = run(options(VesselShape::jar, 36, 0.75, 1, 0.1, seed));
    SCOPED_TRACE(seed);
    EXPECT_LT(r.score.angle_deg, 0.5);          // measured 0.17, 0.06
    EXPECT_LT(r.score.offset, 0.01);            // 0.18 %, 0.39 %
    EXPECT_LT(r.score.profile_median, 0.005);   // 0.07 %, 0.35 %
    EXPECT_LT(r.score.profile_p90, 0.015);      // 0.20 %, 0.53 %
    EXPECT_TRUE(r.score.up_right);
    ASSERT_TRUE(r.record.has_rim);
    EXPECT_LT(r.score.rim_diameter, 0.02);      // 0.26 %, 0.65 %
    EXPECT_NEAR(r.record.rim_share, 0.1, 0.02);
    EXPECT_LT(r.score.angle_deg, 3 * r.record.angle_uncertainty_deg);
  }
}

// A small body sherd of the jar's rounded shoulder is nearly a piece of a sphere: axes some
// degrees apart fit it about equally well. The record must say so, not state a tight axis.
TEST(VesselRecord, LooseBodySherdIsWarned) {
  const PotteryRun r = run(options(VesselShape::jar, 25, 0.55, 0.8, 0.1, 1));
  EXPECT_GT(r.record.angle_uncertainty_deg, 1.0);  // measured 7.4 (the error: 8.7)
  EXPECT_LT(r.score.angle_deg, 3 * r.record.angle_uncertainty_deg);
  bool warned = false;
  for (const std::string& line : record_log_lines(r.record)) warned = warned || line.rfind("Warning: this piece holds its axis only loosely", 0) == 0;
  EXPECT_TRUE(warned);
  // A rim sherd of a third holds its axis: no such warning.
  const PotteryRun third = run(options(VesselShape::jar, 108, 0.7, 1, 0.1));
  for (const std::string& line : record_log_lines(third.record)) EXPECT_EQ(line.find("only loosely"), std::string::npos) << line;
}

TEST(VesselRecord, BodySherdHasNoRimAndBaseSherdStandsOnItsBase) {
  const PotteryRun body = run(options(VesselShape::jar, 90, 0.3, 0.6, 0.1, 4));
  EXPECT_LT(body.score.angle_deg, 0.5);
  EXPECT_FALSE(body.record.has_rim);  // both ends are breaks
  EXPECT_EQ(body.record.rim_diameter, 0);
  const PotteryRun base = run(options(VesselShape::bowl, 90, 0, 0.5, 0.1));
  EXPECT_LT(base.score.angle_deg, 0.5);  // measured 0.09
  EXPECT_TRUE(base.score.up_right);
  EXPECT_EQ(base.record.up_rule, UpRule::base);
  EXPECT_FALSE(base.record.has_rim);
}

TEST(VesselRecord, IncisedAndOutOfRound) {
  SherdOptions o = options(VesselShape::jar, 108, 0.4, 1, 0.1);
  o.incised = true;
  const PotteryRun incised = run(o);
  EXPECT_LT(incised.score.angle_deg, 0.2);         // measured 0.03
  EXPECT_LT(incised.score.profile_median, 0.005);  // 0.11 %
  // the grooves stand out of the surface of revolution in vertex quality: 1.5 mm deep
  double deepest = 0;
  for (double d : incised.record.distance) deepest = std::min(deepest, d);
  EXPECT_LT(deepest, -1.0);
  o.incised = false, o.out_of_round = 0.01;
  const PotteryRun oval = run(o);
  EXPECT_LT(oval.score.angle_deg, 0.6);  // measured 0.32 (a 1 % oval, 30 % of it; offset 1.4 %, see docs/pottery.md)
  EXPECT_TRUE(oval.score.up_right);
  // The whole oval pot: its axis is its centre line, which the whole wall holds.
  SherdOptions whole = options(VesselShape::jar, 360, 0, 1, 0.05);
  whole.out_of_round = 0.01, whole.edge = 1;
  const PotteryRun pot = run(whole);
  EXPECT_LT(pot.score.angle_deg, 0.2);   // measured 0.04
  EXPECT_LT(pot.score.offset, 0.002);    // 0.02 %
}

TEST(VesselRecord, GivenAxisAndFlip) {
  const rktest::Sherd sh = rktest::make_sherd(options(VesselShape::jar, 108, 0.7, 1, 0.1));
  VesselRecordParams p;
  p.given_axis = AxisLine{sh.axis_point, -sh.axis_direction};  // the sign does not matter
  const VesselRecord r = record_vessel(Surface(sh.mesh), p);
  EXPECT_FALSE(r.fit.has_value());
  EXPECT_GT(r.axis.direction.dot(sh.axis_direction), 1 - 1e-12);
  EXPECT_LT(rktest::score_record(sh, r).profile_median, 0.003);
  p.flip = true;
  const VesselRecord turned = record_vessel(Surface(sh.mesh), p);
  EXPECT_LT(turned.axis.direction.dot(sh.axis_direction), -1 + 1e-12);
  EXPECT_TRUE(turned.flipped);
  p.given_axis = AxisLine{sh.axis_point, Vec3::Zero()};
  EXPECT_THROW(record_vessel(Surface(sh.mesh), p), InputError);
}

TEST(VesselRecord, RefusesWhatTurnsAboutNoAxis) {
  auto message = [](const TriMesh& m) {
    try {
      record_vessel(Surface(m));
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  const std::string sphere = message(rktest::sphere(30, 4, 0.1));
  EXPECT_TRUE(sphere.find("every axis") != std::string::npos || sphere.find("axes fit") != std::string::npos) << sphere;
  EXPECT_NE(message(rktest::height_field([](double, double) { return 0.0; }, 30, 40)).find("parallel"), std::string::npos);
  TriMesh blob = rktest::sphere(30, 4);
  for (Vec3& p : blob.vertices) {
    const double theta = std::atan2(p.y(), p.x()), phi = std::acos(std::clamp(p.z() / p.norm(), -1.0, 1.0));
    p *= 1 + 0.25 * std::sin(3 * theta) * std::sin(2 * phi) + 0.15 * std::cos(5 * phi);
  }
  const std::string b = message(blob);
  EXPECT_TRUE(b.find("no axis of revolution") != std::string::npos || b.find("no piece of a surface") != std::string::npos) << b;
}

// The round trip of issue 42: a profile drawing -> "Vessel from Profile Drawing" -> this filter ->
// the drawing's profile back (the drawing's reading is within 1 % of the height, its own test).
TEST(VesselRecord, RoundTripFromAProfileDrawing) {
  const rktest::VesselDrawing d = rktest::vessel_drawing();
  VesselParams vp;
  const VesselProfile profile = read_vessel_profile(d.image, vp);
  const TriMesh vessel = revolve_vessel_profile(profile, vp);  // px; height = -y
  const VesselRecord r = record_vessel(Surface(vessel));
  EXPECT_EQ(r.up_rule, UpRule::base);
  ASSERT_TRUE(r.has_rim);
  double lowest = INFINITY;  // the drawing's base, in its heights (-y)
  for (const Vec2& q : d.section) lowest = std::min(lowest, q.y());
  const std::vector<Vec2> revolved = vessel_profile_section(profile, 1);
  std::vector<double> to_drawing, to_revolved;
  for (const ProfileCurve& c : r.profile)
    for (const Vec2& q : c.points) {
      to_drawing.push_back(rktest::distance_to_polygon(Vec2(q.x(), q.y() + lowest), d.section) / d.height);
      double base = INFINITY;
      for (const Vec2& v : revolved) base = std::min(base, v.y());
      to_revolved.push_back(rktest::distance_to_polygon(Vec2(q.x(), q.y() + base), revolved) / d.height);
    }
  ASSERT_GT(to_drawing.size(), 100u);
  EXPECT_LT(rktest::percentile(to_revolved, 0.9), 0.002);  // this filter alone: the profile it was turned from
  EXPECT_LT(rktest::percentile(to_drawing, 0.5), 0.005);   // and the drawing's
  EXPECT_LT(rktest::percentile(to_drawing, 0.9), 0.01);
}
