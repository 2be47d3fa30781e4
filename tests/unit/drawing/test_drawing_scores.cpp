// The corpus checks that need no annotation (tests/support/drawing_scores.h) on results whose
// answer is known: a raised disc and a flat one; a vessel revolved from the drawing's own section
// and one 5 % too wide.
#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

#include "drawing_scores.h"
#include "reliefkit/drawing/drawing_relief.h"
#include "reliefkit/drawing/vessel_profile.h"
#include "vessels.h"

using namespace reliefkit;

namespace {

// A disc of radius 60 px drawn at (100, 100) on a 200 x 200 drawing, and a grid over it whose
// height is `inside` within 60 px of the centre and `outside` beyond.
struct DiscRelief {
  cv::Mat drawing;
  TriMesh grid;
  std::vector<double> height;
};

DiscRelief disc_relief(double inside, double outside) {
  DiscRelief d;
  d.drawing = cv::Mat(200, 200, CV_8UC1, cv::Scalar(255));
  cv::circle(d.drawing, cv::Point(100, 100), 60, cv::Scalar(0), 2, cv::LINE_AA);
  d.grid = drawing_grid(200, 200, 2, 1.0);
  for (const Vec3& v : d.grid.vertices) d.height.push_back(std::hypot(v.x() - 100, -v.y() - 100) < 60 ? inside : outside);
  return d;
}

}  // namespace

TEST(DrawingScores, ARaisedDiscPassesAndAFlatOneFails) {
  const double step = 0.005 * 199;  // 0.5 % of the relief's width
  DiscRelief raised = disc_relief(step, 0);
  const rktest::ReliefScore good = rktest::score_relief(raised.drawing, raised.grid, raised.height, 1.0);
  EXPECT_EQ(good.objects, 1);
  ASSERT_EQ(good.raised.size(), 1u);
  EXPECT_GT(good.raised[0], 0.99);
  EXPECT_GT(good.paper_flat, 0.99);
  EXPECT_TRUE(good.pass) << good.cause;
  DiscRelief flat = disc_relief(0, 0);
  const rktest::ReliefScore bad = rktest::score_relief(flat.drawing, flat.grid, flat.height, 1.0);
  EXPECT_LT(bad.raised[0], 0.01);
  EXPECT_FALSE(bad.pass);
  EXPECT_NE(bad.cause.find("raised"), std::string::npos);
  DiscRelief sunk = disc_relief(step, -step);  // the paper below the ground
  const rktest::ReliefScore below = rktest::score_relief(sunk.drawing, sunk.grid, sunk.height, 1.0);
  EXPECT_GT(below.below_paper, 0.5);
  EXPECT_FALSE(below.pass);
}

TEST(DrawingScores, TheDrawingsOwnSectionPassesAndAVessel5PercentWideFails) {
  const rktest::VesselDrawing d = rktest::vessel_drawing();
  VesselProfile p;
  p.axis_x = d.axis_x, p.closed = true, p.pen_width = 2;
  for (const Vec2& q : d.section) p.outline.emplace_back(d.axis_x - q.x(), -q.y());
  const TriMesh vessel = revolve_vessel_profile(p, {});
  const rktest::VesselScore good = rktest::score_vessel(d.image, vessel, 1.0);
  EXPECT_GT(good.coverage, 0.95);
  EXPECT_LT(good.median_error, 0.01);
  EXPECT_LT(good.p90_error, 0.02);
  EXPECT_NEAR(good.drawn_axis, d.axis_x, 1.0);
  EXPECT_TRUE(good.pass) << good.cause;
  TriMesh wide = vessel;
  for (Vec3& v : wide.vertices) v.x() = d.axis_x + 1.05 * (v.x() - d.axis_x), v.z() *= 1.05;
  const rktest::VesselScore bad = rktest::score_vessel(d.image, wide, 1.0);
  EXPECT_NEAR(bad.median_error, 0.05, 0.012);
  EXPECT_FALSE(bad.pass);
}
