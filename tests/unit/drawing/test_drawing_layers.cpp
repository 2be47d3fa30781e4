// The chapter 7 logic the adapters call (reliefkit/drawing/drawing_relief.h "curves and levels on the
// relief", base_library.h's view helpers), with known answers: curves in mesh units, region levels
// per position, curves placed on a projected and on a grid relief, reading order of outlines,
// outlines in mesh units, the border test, a round object's second view, a model chosen by name.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "reliefkit/drawing/base_library.h"
#include "reliefkit/drawing/drawing_relief.h"

using namespace reliefkit;

namespace {

DrawingCurves two_curves() {
  DrawingCurves dc;
  dc.width = 20, dc.height = 10;
  dc.curves = {{Vec2(2, 3), Vec2(4, 3), Vec2(6, 3)}, {Vec2(10, 8), Vec2(10, 6)}};
  return dc;
}

}  // namespace

TEST(DrawingLayers, PolylinesAreTheCurvesInMeshUnitsWithYUp) {
  const Polylines pl = drawing_polylines(two_curves(), 0.5);
  ASSERT_EQ(pl.points.size(), 5u);
  EXPECT_EQ(pl.points[1], Vec3(2, -1.5, 0));
  EXPECT_EQ(pl.points[3], Vec3(5, -4, 0));
  EXPECT_EQ(pl.strength, (std::vector<double>{0, 0, 0, 1, 1}));
  // Segments join successive points of one curve, never two curves.
  ASSERT_EQ(pl.segments.size(), 3u);
  EXPECT_EQ(pl.segments[1], (std::array<int, 2>{1, 2}));
  EXPECT_EQ(pl.segments[2], (std::array<int, 2>{3, 4}));
}

TEST(DrawingLayers, RegionLevelsPerPosition) {
  DrawingInterpretation di;
  di.regions = cv::Mat(4, 6, CV_32S, cv::Scalar(0));
  di.regions(cv::Rect(3, 0, 3, 4)).setTo(1);
  di.regions.at<int>(2, 1) = -1;  // a curve pixel
  di.region_height = {0, 3};
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const std::vector<Vec2> at = {Vec2(0, 0), Vec2(4.4, 1), Vec2(2.6, 0), Vec2(1, 2), Vec2(6, 0), Vec2(nan, nan), Vec2(-1, 0)};
  // Rounded to the pixel: (2.6, 0) is in pixel 3, region 1; (6, 0) is outside the 6 px wide image.
  EXPECT_EQ(region_levels(di, at), (std::vector<double>{0, 3, 3, -1, -1, -1, -1}));
}

TEST(DrawingLayers, CurvesOnAProjectedReliefGoToTheNearestCoveredVertexPlusTheOffset) {
  // Three covered vertices at pixels (2, 3), (6, 3), (10, 7); one not covered.
  const double nan = std::numeric_limits<double>::quiet_NaN();
  DrawingProjection proj;
  proj.pixel = {Vec2(2, 3), Vec2(6, 3), Vec2(10, 7), Vec2(nan, nan)};
  proj.right = Vec3(1, 0, 0), proj.up = Vec3(0, 0, 1);
  proj.pixel_size = 0.5;
  proj.edge_px = 2;  // cells of 4 px
  TriMesh relief;
  relief.vertices = {Vec3(0, 10, 0), Vec3(2, 11, 0), Vec3(4, 12, 2), Vec3(9, 9, 9)};
  DrawingCurves dc = two_curves();
  dc.curves.push_back({Vec2(19, 0), Vec2(19, 1)});  // far from every covered vertex: dropped
  const Polylines pl = curves_on_projected_relief(dc, proj, relief);
  ASSERT_EQ(pl.points.size(), 7u);
  EXPECT_EQ(pl.points[0], Vec3(0, 10, 0));                      // on vertex 0
  EXPECT_EQ(pl.points[1], Vec3(0, 10, 0) + 0.5 * Vec3(2, 0, 0));  // 2 px right of vertex 0 (nearest of 0 and 1: 0 first)
  EXPECT_EQ(pl.points[2], Vec3(2, 11, 0));                      // on vertex 1
  // (10, 8): vertex 2 plus 1 px down the image = -up.
  EXPECT_EQ(pl.points[3], Vec3(4, 12, 2) - 0.5 * Vec3(0, 0, 1));
  // The dropped curve's points lose their segment; the others keep theirs.
  EXPECT_EQ(pl.segments.size(), 3u);
  for (const auto& s : pl.segments) EXPECT_LT(s[1], 5);
}

TEST(DrawingLayers, CurvesOnAGridReliefTakeTheBilinearHeightBelowThem) {
  // A grid over pixels 0..8 x 0..4, one vertex every 2 px, heights h = x_px + 10 y_px (bilinear: exact).
  const cv::Rect area(0, 0, 9, 5);
  const double cell = 2, px = 0.25;
  const TriMesh grid = drawing_grid(area.width, area.height, cell, px);
  std::vector<double> h;
  for (const auto& v : grid.vertices) h.push_back(v.x() / px + 10 * (-v.y() / px));
  DrawingCurves dc;
  dc.width = 9, dc.height = 5;
  dc.curves = {{Vec2(1, 1), Vec2(3.5, 2.5), Vec2(8, 4)}};
  const Polylines pl = curves_on_grid_relief(dc, px, area, cell, h, DrawingBase::Plane, 1);
  ASSERT_EQ(pl.points.size(), 3u);
  EXPECT_NEAR(pl.points[0].z(), 1 + 10 * 1, 1e-12);
  EXPECT_NEAR(pl.points[1].z(), 3.5 + 10 * 2.5, 1e-12);
  EXPECT_NEAR(pl.points[2].z(), 8 + 10 * 4, 1e-12);
  EXPECT_EQ(pl.points[1].head<2>(), Vec2(3.5 * px, -2.5 * px));
  // On a cylinder the point is laid like the grid: at radius R + h.
  const double circumference = 9 * px, R = circumference / (2 * M_PI);
  const Polylines cyl = curves_on_grid_relief(dc, px, area, cell, h, DrawingBase::Cylinder, circumference);
  const Vec3& q = cyl.points[1];
  EXPECT_NEAR(std::hypot(q.x(), q.z()), R + 3.5 + 25, 1e-9);
  EXPECT_THROW(curves_on_grid_relief(dc, px, area, cell, {1, 2}, DrawingBase::Plane, 1), InputError);
}

TEST(DrawingViews, ReadingOrderIsTopToBottomThenLeftToRightInARow) {
  auto outline = [](int x, int y, int w, int h) {
    DrawingOutline o;
    o.box = cv::Rect(x, y, w, h);
    return o;
  };
  // A row of two (their heights overlap by more than half) above a third; given out of order.
  std::vector<DrawingOutline> o = {outline(0, 300, 100, 100), outline(200, 10, 100, 100), outline(0, 40, 100, 100)};
  sort_reading_order(o);
  EXPECT_EQ(o[0].box.x, 0);
  EXPECT_EQ(o[0].box.y, 40);
  EXPECT_EQ(o[1].box.x, 200);
  EXPECT_EQ(o[2].box.y, 300);
}

TEST(DrawingViews, OutlineInUnitsTurnsImageYUp) {
  const Outline o = outline_in_units({Vec2(2, 4), Vec2(10, 0)}, 0.1);
  ASSERT_EQ(o.size(), 2u);
  EXPECT_NEAR(o[0].x(), 0.2, 1e-15);
  EXPECT_NEAR(o[0].y(), -0.4, 1e-15);
  EXPECT_NEAR(o[1].x(), 1.0, 1e-15);
  EXPECT_EQ(o[1].y(), 0);
}

TEST(DrawingViews, TouchesFrameWithinOnePercentOrThreePixels) {
  const cv::Rect frame(100, 100, 1000, 500);  // 1 %: 10 px
  EXPECT_FALSE(touches_frame(cv::Rect(111, 111, 500, 300), frame));
  EXPECT_TRUE(touches_frame(cv::Rect(110, 200, 500, 300), frame));   // 10 px from the left
  EXPECT_TRUE(touches_frame(cv::Rect(200, 200, 890, 100), frame));   // right edge at 1090
  EXPECT_TRUE(touches_frame(cv::Rect(200, 200, 100, 391), frame));   // bottom edge at 591
  // Small frames: at least 3 px.
  EXPECT_TRUE(touches_frame(cv::Rect(200, 103, 10, 10), cv::Rect(100, 100, 200, 200)));
  EXPECT_FALSE(touches_frame(cv::Rect(200, 104, 10, 10), cv::Rect(100, 100, 200, 200)));
}

TEST(DrawingViews, ARoundObjectsOneViewServesAsTheOtherToo) {
  const Outline o = {Vec2(0, 0), Vec2(1, 0), Vec2(0, 1)};
  const auto front = round_object_views({{ViewKind::Front, o}});
  ASSERT_EQ(front.size(), 2u);
  EXPECT_EQ(front[1].kind, ViewKind::Side);
  EXPECT_EQ(front[1].outline, o);
  const auto side = round_object_views({{ViewKind::Side, o}});
  ASSERT_EQ(side.size(), 2u);
  EXPECT_EQ(side[1].kind, ViewKind::Front);
  EXPECT_EQ(round_object_views({{ViewKind::Top, o}}).size(), 1u);
  EXPECT_EQ(round_object_views({{ViewKind::Front, o}, {ViewKind::Top, o}}).size(), 2u);
}

TEST(DrawingViews, NamedMatchIgnoresCaseAndRefusesAnUnknownName) {
  BaseLibrary lib;
  lib.models.resize(3);
  lib.models[0].name = "lamp_01", lib.models[1].name = "Bowl_02", lib.models[2].name = "jug_03";
  std::vector<BaseMatch> ranked(3);
  for (int k = 0; k < 3; ++k) ranked[size_t(k)].model = 2 - k, ranked[size_t(k)].score = k;
  EXPECT_EQ(named_match(lib, ranked, "bowl_02").model, 1);
  EXPECT_EQ(named_match(lib, ranked, "bowl_02").score, 1);
  EXPECT_EQ(named_match(lib, ranked, "LAMP_01").model, 0);
  try {
    named_match(lib, ranked, "krater_09");
    FAIL() << "no error for an unknown model";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("e.g. jug_03"), std::string::npos) << e.what();
  }
}
