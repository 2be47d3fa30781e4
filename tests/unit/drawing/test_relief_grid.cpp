// The grid "Relief from Line Drawing" builds a relief on (reliefkit/drawing/drawing_relief.h,
// relief_grid.cpp): its extent round the curves, its step height, its spacing (automatic, coarsened
// for a large drawing, or given) and each vertex's pixel.
#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

#include "reliefkit/base/scale.h"
#include "reliefkit/drawing/drawing_interpretation.h"
#include "reliefkit/drawing/drawing_relief.h"
#include "reliefkit/drawing/line_drawing.h"

using namespace reliefkit;

namespace {

// A rectangle outline, its line's centre from (60, 50) to (240, 150), on a 300 x 200 drawing.
struct Rectangle {
  DrawingCurves curves;
  DrawingInterpretation interpretation;
};

const Rectangle& rectangle() {
  static const Rectangle r = [] {
    cv::Mat img(200, 300, CV_8UC1, cv::Scalar(255));
    cv::rectangle(img, cv::Point(60, 50), cv::Point(240, 150), cv::Scalar(0), 2);
    Rectangle out;
    out.curves = extract_drawing_curves(img);
    out.interpretation = interpret_drawing(out.curves);
    return out;
  }();
  return r;
}

}  // namespace

TEST(ReliefGrid, TheAreaIsTheCurvesGrownByFourStepWidthsWithTheStepAPercentOfItsWidth) {
  const Rectangle& r = rectangle();
  ReliefGridParams p;
  p.margin = 4, p.pixel_size = 0.1;
  const ReliefGrid g = relief_grid(r.curves, r.interpretation, p);
  // The curves run at the line's centre, 60.5 .. 240.5 and 50.5 .. 150.5; 4 x 4 + 4 = 20 px round them.
  EXPECT_NEAR(g.area.x, 40, 1.5);
  EXPECT_NEAR(g.area.y, 30, 1.5);
  EXPECT_NEAR(g.area.x + g.area.width, 261, 1.5);
  EXPECT_NEAR(g.area.y + g.area.height, 171, 1.5);
  EXPECT_EQ(g.area, relief_area(r.curves, 4));
  EXPECT_DOUBLE_EQ(relief_step_height(0.5, g.area, 0.1), 0.005 * g.area.width * 0.1);
  EXPECT_FALSE(g.coarsened());
  EXPECT_LE(g.cell, 2.0);  // at most half the step width
  ASSERT_EQ(g.pixel.size(), g.grid.vertices.size());
  EXPECT_NEAR(g.pixel.front().x(), g.area.x, 1e-9);
  EXPECT_NEAR(g.pixel.front().y(), g.area.y, 1e-9);
  EXPECT_NEAR(g.pixel.back().x(), g.area.x + g.area.width - 1, 1e-9);
  EXPECT_NEAR(g.pixel.back().y(), g.area.y + g.area.height - 1, 1e-9);
  for (size_t v = 0; v < g.pixel.size(); v += 97) {
    EXPECT_NEAR(g.grid.vertices[v].x(), g.pixel[v].x() * 0.1, 1e-9);
    EXPECT_NEAR(g.grid.vertices[v].y(), -g.pixel[v].y() * 0.1, 1e-9);
  }
}

TEST(ReliefGrid, ALargeDrawingIsCoarsenedUnderTheVertexBudgetAndAGivenSpacingIsKept) {
  const Rectangle& r = rectangle();
  ReliefGridParams p;
  p.max_vertices = 1000;
  const ReliefGrid g = relief_grid(r.curves, r.interpretation, p);
  EXPECT_TRUE(g.coarsened());
  EXPECT_NEAR(g.cell, std::sqrt(double(g.area.width) * g.area.height / 1000), 1e-9);
  EXPECT_GT(g.wanted_vertices, 1000);
  EXPECT_LE(g.grid.n_vertices(), 1150);  // the budget fills the area; a row and a column more at its edges
  p.cell = 5;  // the user's spacing: kept, whatever the budget
  const ReliefGrid given = relief_grid(r.curves, r.interpretation, p);
  EXPECT_FALSE(given.coarsened());
  EXPECT_EQ(given.cell, 5);
  EXPECT_NEAR(given.pixel[1].x() - given.pixel[0].x(), 5, 1e-9);
}

TEST(ReliefGrid, ABadPixelSizeIsRefused) {
  ReliefGridParams p;
  p.pixel_size = 0;
  EXPECT_THROW(relief_grid(rectangle().curves, rectangle().interpretation, p), InputError);
}
