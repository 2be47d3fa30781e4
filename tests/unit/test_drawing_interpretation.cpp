// Interpreting line drawings (reliefkit/drawing_interpretation.h): drawings rendered here from known
// nested reliefs; every step's sign and height must come out as drawn.
#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

#include "reliefkit/drawing_interpretation.h"

using namespace reliefkit;

namespace {

// An object (rectangle 40..560) holding a raised disc, a raised ring with a raised disc inside it
// (two levels), and a raised square cut in two by a line (a junction of three curves).
cv::Mat nested_drawing() {
  cv::Mat img(600, 600, CV_8UC1, cv::Scalar(255));
  cv::rectangle(img, {40, 40}, {560, 560}, cv::Scalar(0), 2, cv::LINE_AA);
  cv::circle(img, {160, 160}, 70, cv::Scalar(0), 2, cv::LINE_AA);
  cv::circle(img, {420, 170}, 90, cv::Scalar(0), 2, cv::LINE_AA);
  cv::circle(img, {420, 170}, 40, cv::Scalar(0), 2, cv::LINE_AA);
  cv::rectangle(img, {120, 340}, {460, 480}, cv::Scalar(0), 2, cv::LINE_AA);
  cv::line(img, {290, 340}, {290, 480}, cv::Scalar(0), 2, cv::LINE_AA);
  return img;
}

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
  p.fixed.push_back({k, inner_on_left});  // the inner disc lower than the ring: sunken
  const DrawingInterpretation f = interpret_drawing(c, p);
  const int ring = f.regions.at<int>(100, 420);
  EXPECT_LT(f.region_height[inner], f.region_height[ring]);
  // A contradiction: the same curve fixed both ways.
  p.fixed.push_back({k, !inner_on_left});
  EXPECT_THROW(interpret_drawing(c, p), InputError);
  InterpretationParams bad;
  bad.fixed.push_back({int(c.curves.size()) + 5, true});
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
  // Heights of the free surface against the regions. levels.
  cv::Mat ink(img.rows, img.cols, CV_8U, cv::Scalar(255));
  for (const auto& cv_ : c.curves)
    for (const auto& q : cv_) ink.at<uchar>(int(std::lround(q.y())), int(std::lround(q.x()))) = 0;
  cv::Mat dist;
  cv::distanceTransform(ink, dist, cv::DIST_L2, 5);
  double num = 0, den = 0;
  std::vector<std::pair<double, double>> pairs;  // (level, height)
  for (int v = 0; v < grid.n_vertices(); ++v) {
    const int x = int(std::lround(grid.vertices[v].x())), y = int(std::lround(-grid.vertices[v].y()));
    const int reg = d.regions.at<int>(y, x);
    if (reg < 0 || r.in_margin[size_t(v)]) continue;  // the free surface only (margins are held)
    if (reg == d.regions.at<int>(5, 5)) continue;  // the paper outside the object
    pairs.push_back({double(d.region_height[size_t(reg)]), r.height[size_t(v)]});
    num += pairs.back().first * pairs.back().second, den += pairs.back().first * pairs.back().first;
  }
  const double scale = den > 0 ? num / den : 0;  // the global scale fit
  double s2 = 0;
  for (const auto& [lv, h] : pairs) s2 += (h - scale * lv) * (h - scale * lv);
  const double rms = std::sqrt(s2 / pairs.size()) / (scale > 0 ? scale : 1);
  std::printf("[drawing relief] %d vertices, scale fit %.3f per level, RMS error %.3f step (%zu samples); solve: %s\n",
              grid.n_vertices(), scale, rms, pairs.size(),
              r.relief_solve.summary().c_str());
  EXPECT_GT(scale, 0.5);
  EXPECT_LE(rms, 0.1);
}
