// Interpreting line drawings (reliefkit/drawing_interpretation.h): drawings rendered here from known
// nested reliefs; every step's sign and height must come out as drawn.
#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

#include "drawings.h"
#include "reliefkit/drawing_interpretation.h"

using namespace reliefkit;

namespace {

using rktest::nested_drawing;

int region_of(const DrawingInterpretation& d, int x, int y) { return d.regions.at<int>(y, x); }

}  // namespace

TEST(DrawingInterpretation, NestedReliefsGetTheirLevels) {
  const DrawingCurves c = extract_drawing_curves(nested_drawing());
  const DrawingInterpretation d = interpret_drawing(c);
  const int object = region_of(d, 300, 300), disc = region_of(d, 160, 160), ring = region_of(d, 420, 100),
            inner = region_of(d, 420, 170), left = region_of(d, 200, 410), right = region_of(d, 380, 410);
  for (int r : {object, disc, ring, inner, left, right}) ASSERT_GE(r, 0);
  std::printf("[drawing interpretation] %zu curves, %d regions; heights: object %d, disc %d, ring %d, inner disc %d, "
              "square halves %d / %d\n",
              c.curves.size(), d.region_count, d.region_height[object], d.region_height[disc], d.region_height[ring],
              d.region_height[inner], d.region_height[left], d.region_height[right]);
  const auto& h = d.region_height;
  EXPECT_EQ(h[disc] - h[object], 1);
  EXPECT_EQ(h[ring] - h[object], 1);
  EXPECT_EQ(h[inner] - h[ring], 1);
  EXPECT_GE(std::min(h[left], h[right]) - h[object], 1);
  EXPECT_EQ(std::abs(h[left] - h[right]), 1);  // the dividing line is a step too (Constraint 1)
}

TEST(DrawingInterpretation, FixedDirectionsAreKeptAndContradictionsRefused) {
  const DrawingCurves c = extract_drawing_curves(nested_drawing());
  DrawingInterpretation d = interpret_drawing(c);
  const int inner = d.regions.at<int>(170, 420);
  int k = -1;  // the inner circle's curve: one side is the inner disc
  for (size_t i = 0; i < d.sides.size(); ++i)
    if (d.sides[i][0] == inner || d.sides[i][1] == inner) k = int(i);
  ASSERT_GE(k, 0);
  InterpretationParams p;
  const bool inner_on_left = d.sides[size_t(k)][0] == inner;
  p.overrides.push_back({k, inner_on_left ? CurveOverride::Direction::LeftLower : CurveOverride::Direction::RightLower});  // the inner disc lower than the ring: sunken
  const DrawingInterpretation f = interpret_drawing(c, p);
  const int ring = f.regions.at<int>(100, 420);
  EXPECT_LT(f.region_height[inner], f.region_height[ring]);
  // The same curve named twice is refused.
  p.overrides.push_back({k, CurveOverride::Direction::LeftLower});
  EXPECT_THROW(interpret_drawing(c, p), InputError);
  InterpretationParams bad;
  bad.overrides.push_back({int(c.curves.size()) + 5, CurveOverride::Direction::LeftLower});
  EXPECT_THROW(interpret_drawing(c, bad), InputError);
}

#include "reliefkit/drawing_relief.h"

TEST(DrawingRelief, NestedReliefsReconstructToTheirLevels) {
  const cv::Mat img = nested_drawing();
  const DrawingCurves c = extract_drawing_curves(img);
  const DrawingInterpretation d = interpret_drawing(c);
  DrawingReliefParams p;
  const TriMesh grid = drawing_grid(img.cols, img.rows, 2.0, p.pixel_size);
  const DrawingRelief r = reconstruct_drawing_relief(grid, c, d, p);
  // Heights of the free surface against the regions' levels, after the global scale fit.
  const rktest::LevelFit fit = rktest::fit_levels(grid, p.pixel_size, r, d, {5, 5});
  const double scale = fit.scale, rms = fit.rms_steps;
  std::printf("[drawing relief] %d vertices, scale fit %.3f per level, RMS error %.3f step (%ld samples); solves: %s | %s\n",
              grid.n_vertices(), scale, rms, fit.samples, r.laplacian_solve.summary().c_str(), r.relief_solve.summary().c_str());
  EXPECT_GT(fit.samples, grid.n_vertices() / 4);
  EXPECT_GT(scale, 0.5);
  EXPECT_LE(rms, 0.1);
}
