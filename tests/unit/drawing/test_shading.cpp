// Shading is not structure (issue 23): hatching and cross-hatching recognised as families of
// near-parallel strokes and left out of the regions; objects whose edges are drawn with hatching
// ends, dots or broken lines closed, so that each rises as one body.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <map>
#include <opencv2/imgproc.hpp>

#include "drawings.h"
#include "reliefkit/drawing/drawing_interpretation.h"
#include "reliefkit/drawing/drawing_relief.h"
#include "reliefkit/drawing/line_drawing.h"
#include "reliefkit/drawing/shading.h"

using namespace reliefkit;

namespace {

DrawingCurves automatic_curves(const cv::Mat& image, bool shading = true, bool close_outlines = true) {
  LineDetectionParams p;
  p.sigma = 0;
  p.recognise_shading = shading;
  if (!close_outlines) p.object_gap = 0;
  return extract_drawing_curves(image, p);
}

// The share of a part's pixels (mask) at its most common level, and that level (-1: on a curve).
std::pair<double, int> modal_level(const DrawingInterpretation& di, const cv::Mat& mask) {
  std::map<int, long> count;
  long n = 0;
  for (int y = 0; y < mask.rows; ++y)
    for (int x = 0; x < mask.cols; ++x)
      if (mask.at<uchar>(y, x)) {
        const int r = di.regions.at<int>(y, x);
        ++count[r >= 0 ? di.region_height[size_t(r)] : -1], ++n;
      }
  auto best = count.begin();
  for (auto it = count.begin(); it != count.end(); ++it)
    if (it->second > best->second) best = it;
  return {double(best->second) / std::max(1L, n), best->first};
}

// Curves with their middle point inside `mask`.
std::vector<size_t> curves_inside(const DrawingCurves& c, const cv::Mat& mask) {
  std::vector<size_t> out;
  for (size_t k = 0; k < c.curves.size(); ++k) {
    const Vec2 m = c.curves[k][c.curves[k].size() / 2];
    if (mask.at<uchar>(int(std::lround(m.y())), int(std::lround(m.x())))) out.push_back(k);
  }
  return out;
}

}  // namespace

// The hatched lens and the cross-hatched rectangle: their strokes are shading, the three closed
// outlines are not. Measured: of the 272 curves inside the two sections 0.952 are shading.
TEST(DrawingShading, HatchingAndCrossHatchingAreShadingOutlinesAreNot) {
  const rktest::HatchedSections d = rktest::hatched_sections_drawing();
  const DrawingCurves c = automatic_curves(d.image);
  long inside = 0, shading = 0;
  cv::Mat sections = d.lens | d.rect;
  for (size_t k : curves_inside(c, sections)) ++inside, shading += c.shading[k];
  long outlines = 0, outline_shading = 0;
  for (size_t k = 0; k < c.curves.size(); ++k) {
    const auto& cu = c.curves[k];
    if (cu.size() > 3 && (cu.front() - cu.back()).norm() <= 3 && c.total_length() > 0) ++outlines, outline_shading += c.shading[k];
  }
  std::printf("[shading, hatched sections] %zu curves; inside the sections %ld, shading %.3f; closed curves %ld, shading %ld\n",
              c.curves.size(), inside, double(shading) / inside, outlines, outline_shading);
  EXPECT_GE(inside, 100);
  EXPECT_GE(double(shading) / inside, 0.9);
  EXPECT_GE(outlines, 3);
  EXPECT_EQ(outline_shading, 0);
}

// A family needs four lines: two parallel lines (a thin wall's edges) and three are structure, six
// are hatching.
TEST(DrawingShading, AFamilyNeedsFourParallelLines) {
  for (int lines : {2, 3, 6}) {
    cv::Mat img(300, 400, CV_8UC1, cv::Scalar(255));
    for (int k = 0; k < lines; ++k) cv::line(img, {60, 80 + 10 * k}, {340, 95 + 10 * k}, cv::Scalar(0), 1, cv::LINE_AA);
    const DrawingCurves c = automatic_curves(img);
    long shading = 0;
    for (char s : c.shading) shading += s;
    std::printf("[shading, %d parallel lines 10 px apart] %zu curves, %ld shading\n", lines, c.curves.size(), shading);
    if (lines < 4) EXPECT_EQ(shading, 0) << lines;
    else EXPECT_GE(shading, lines - 1) << lines;
  }
}

// Hatching that ends on the outlines no longer cuts its section into strips: each section rises at
// one level and the blank disc stands one level above the cross-hatched rectangle. Measured: lens
// 1.000, rectangle 0.987, disc 1.000 at their levels; with the strokes taken as lines the lens
// climbs a staircase (33 levels, none holding more than 0.043 of it).
TEST(DrawingInterpretation, HatchedSectionsRiseWholeAndFlat) {
  const rktest::HatchedSections d = rktest::hatched_sections_drawing();
  const DrawingInterpretation di = interpret_drawing(automatic_curves(d.image));
  const auto [lens, lens_level] = modal_level(di, d.lens);
  const auto [rect, rect_level] = modal_level(di, d.rect);
  const auto [disc, disc_level] = modal_level(di, d.disc);
  std::printf("[hatched sections] lens %.3f at level %d, rectangle %.3f at %d, disc %.3f at %d\n", lens, lens_level, rect,
              rect_level, disc, disc_level);
  EXPECT_GE(lens, 0.95);
  EXPECT_GE(lens_level, 1);
  EXPECT_GE(rect, 0.95);
  EXPECT_GE(rect_level, 1);
  EXPECT_GE(disc, 0.95);
  EXPECT_EQ(disc_level, rect_level + 1);
  const DrawingInterpretation lines = interpret_drawing(automatic_curves(d.image, false));
  std::map<int, long> count;  // the lens's pixels per level, off the curves
  long n = 0;
  for (int y = 0; y < d.lens.rows; ++y)
    for (int x = 0; x < d.lens.cols; ++x) {
      const int r = lines.regions.at<int>(y, x);
      if (d.lens.at<uchar>(y, x) && r >= 0) ++count[lines.region_height[size_t(r)]], ++n;
    }
  long most = 0;
  for (const auto& [level, k] : count) most = std::max(most, k);
  std::printf("[hatched sections, strokes taken as lines] lens: %zu levels, the most common holds %.3f of it\n",
              count.size(), double(most) / n);
  EXPECT_GT(count.size(), 10u);
  EXPECT_LT(double(most) / n, 0.5);
}

namespace {
// Crop of the shared plate of stone tools (tests/data/drawings): a point well inside each of its 14
// objects (views and hatched sections, by eye) and 9 points of paper, some between two views.
const int kPlateObjects[][2] = {{150, 190}, {350, 190}, {600, 200},  {830, 220}, {1060, 180}, {620, 356}, {170, 580},
                                {290, 636}, {520, 600}, {810, 600}, {1020, 600}, {160, 744}, {536, 752}, {820, 770}};
const int kPlatePaper[][2] = {{200, 390}, {400, 400}, {920, 380}, {1120, 420}, {360, 680},
                              {700, 230}, {230, 620}, {524, 704}, {870, 736}};

// Objects with at least 0.9 of the region pixels within 12 px of their point raised; paper points
// at level 0.
std::pair<int, int> plate_objects_and_paper(const DrawingInterpretation& di) {
  int raised = 0, paper = 0;
  for (const auto& p : kPlateObjects) {
    long n = 0, up = 0;
    for (int dy = -12; dy <= 12; ++dy)
      for (int dx = -12; dx <= 12; ++dx) {
        const int r = dx * dx + dy * dy <= 144 ? di.regions.at<int>(p[1] + dy, p[0] + dx) : -1;
        if (r >= 0) ++n, up += di.region_height[size_t(r)] >= 1;
      }
    raised += n > 0 && up >= 0.9 * n;
  }
  for (const auto& p : kPlatePaper) {
    const int r = di.regions.at<int>(p[1], p[0]);
    paper += r >= 0 && di.region_height[size_t(r)] == 0;
  }
  return {raised, paper};
}
}  // namespace

// Issue 23: a publication plate of stone tools (engraved shading, edges drawn by hatching ends and
// dots, hatched sections) rises object by object. Measured: 14 of 14 objects raised, 6 of 9 paper
// points at the ground (the views of tool 10, and tool 11 and its section, drawn less than 12 px
// apart, are closed as one object); with neither the shading recognised nor the outlines closed,
// 3 of 14 (the former "lines of bumps").
TEST(DrawingInterpretation, APlateOfToolsRisesObjectByObject) {
  const cv::Mat plate = read_drawing_image(RELIEFKIT_TEST_DRAWINGS "/lithic_plate_morar_quartz_crop.jpg");
  const DrawingCurves c = automatic_curves(plate);
  const auto [raised, paper] = plate_objects_and_paper(interpret_drawing(c));
  const auto [before, before_paper] = plate_objects_and_paper(interpret_drawing(automatic_curves(plate, false, false)));
  std::printf("[plate crop] %zu curves (%d outline pieces); objects raised %d of 14, paper %d of 9; without shading and "
              "outlines: %d of 14\n", c.curves.size(), c.outline_pieces, raised, paper, before);
  EXPECT_GE(raised, 13);
  EXPECT_GE(paper, 5);
  EXPECT_LE(before, 4);
}

// An object whose edge is drawn with dots (stippling, which is no line) and hatching inside: its
// outline is closed from the ink and the object rises whole. Measured: 1.000 raised (0.000 without).
TEST(DrawingInterpretation, AnEdgeDrawnWithDotsIsClosed) {
  cv::Mat img(500, 500, CV_8UC1, cv::Scalar(255)), inside(img.size(), CV_8U, cv::Scalar(0));
  for (int k = 0; k < 140; ++k) {  // a dot every 7.5 px
    const double t = 2 * M_PI * k / 140;
    cv::circle(img, {int(250 + 180 * std::cos(t)), int(250 + 150 * std::sin(t))}, 2, cv::Scalar(0), -1, cv::LINE_AA);
  }
  cv::ellipse(inside, {250, 250}, {165, 135}, 0, 0, 360, cv::Scalar(255), -1);
  cv::Mat inner = inside.clone();
  cv::erode(inner, inner, cv::getStructuringElement(cv::MORPH_ELLIPSE, {21, 21}));
  for (int y = 150; y < 350; y += 9) cv::line(img, {200, y}, {300, y + 30}, cv::Scalar(0), 1, cv::LINE_AA);
  for (bool close : {true, false}) {
    const DrawingInterpretation di = interpret_drawing(automatic_curves(img, true, close));
    long n = 0, up = 0;
    for (int y = 0; y < img.rows; ++y)
      for (int x = 0; x < img.cols; ++x) {
        const int r = di.regions.at<int>(y, x);
        if (inner.at<uchar>(y, x) && r >= 0) ++n, up += di.region_height[size_t(r)] >= 1;
      }
    std::printf("[dotted edge, outlines %s] interior raised %.3f\n", close ? "closed" : "not closed", double(up) / n);
    if (close) EXPECT_GE(double(up) / n, 0.95);
    else EXPECT_LT(double(up) / n, 0.5);
  }
}

// Issue 23: the free surface bounded. On the plate crop eq. 7.6 carries the margins' bends into the
// paper between the tools; each free vertex is now held within half a step of its region's level
// and never below the ground. Measured: heights -0.001 to 2.050 steps (levels 0 to 2), 65,102 vertices
// held; without the bound (broken on purpose) the paper sinks to -0.172 steps.
TEST(DrawingRelief, TheFreeSurfaceStaysNearItsLevelAboveTheGround) {
  const cv::Mat plate = read_drawing_image(RELIEFKIT_TEST_DRAWINGS "/lithic_plate_morar_quartz_crop.jpg");
  const DrawingCurves c = automatic_curves(plate);
  for (const auto& curve : c.curves) ASSERT_GE(curve.size(), 2u);
  const DrawingInterpretation di = interpret_drawing(c);
  DrawingReliefParams p;
  const TriMesh grid = drawing_grid(plate.cols, plate.rows, 2.0, p.pixel_size);
  const DrawingRelief r = reconstruct_drawing_relief(grid, c, di, p);
  const int top = *std::max_element(di.region_height.begin(), di.region_height.end());
  const auto [lo, hi] = std::minmax_element(r.height.begin(), r.height.end());
  double worst = 0;  // beyond half a step of the region's level, free vertices
  for (int v = 0; v < grid.n_vertices(); ++v) {
    const Vec3& q = grid.vertices[size_t(v)];
    const int reg = di.regions.at<int>(int(std::lround(-q.y())), int(std::lround(q.x())));
    if (reg >= 0 && !r.in_margin[size_t(v)])
      worst = std::max(worst, std::abs(r.height[size_t(v)] - di.region_height[size_t(reg)]) - 0.5);
  }
  std::printf("[plate crop relief] %d vertices, levels 0 to %d; heights %.3f to %.3f steps; %ld vertices held; worst "
              "beyond half a step %.1e\n", grid.n_vertices(), top, *lo, *hi, r.bounded_vertices, worst);
  EXPECT_GT(r.bounded_vertices, 0);
  EXPECT_GE(*lo, -2e-3);
  EXPECT_LE(*hi, top + 0.5 + 2e-3);
  EXPECT_LE(worst, 2e-3);
}

// Shading engraved on request: inside the hatched lens the relief dips 0.2 step along the strokes
// and keeps its level between them; without the option the lens is flat. Measured: on the strokes
// 0.80 steps (the lens at level 1), between them 1.000; without: 1.000 on both.
TEST(DrawingRelief, ShadingEngravedAsFineGrooves) {
  const rktest::HatchedSections d = rktest::hatched_sections_drawing();
  const DrawingCurves c = automatic_curves(d.image);
  const DrawingInterpretation di = interpret_drawing(c);
  cv::Mat strokes(d.image.size(), CV_8U, cv::Scalar(255)), dist;
  for (size_t k = 0; k < c.curves.size(); ++k)
    if (di.shading[k])
      for (const Vec2& q : c.curves[k]) strokes.at<uchar>(int(std::lround(q.y())), int(std::lround(q.x()))) = 0;
  cv::distanceTransform(strokes, dist, cv::DIST_L2, cv::DIST_MASK_5);
  for (double depth : {0.2, 0.0}) {
    DrawingReliefParams p;
    p.shading_depth = depth;
    const TriMesh grid = drawing_grid(d.image.cols, d.image.rows, 2.0, p.pixel_size);
    const DrawingRelief r = reconstruct_drawing_relief(grid, c, di, p);
    double on = 0, off = 0;
    long n_on = 0, n_off = 0;
    for (int v = 0; v < grid.n_vertices(); ++v) {
      const int x = int(std::lround(grid.vertices[size_t(v)].x())), y = int(std::lround(-grid.vertices[size_t(v)].y()));
      if (!d.lens.at<uchar>(y, x)) continue;
      const float s = dist.at<float>(y, x);
      if (s == 0) on += r.height[size_t(v)], ++n_on;
      else if (s >= 3) off += r.height[size_t(v)], ++n_off;
    }
    std::printf("[engraved shading, depth %.1f] lens on the strokes %.3f, between them %.3f steps\n", depth, on / n_on,
                off / n_off);
    EXPECT_NEAR(on / n_on, 1 - depth, 0.05) << depth;
    EXPECT_NEAR(off / n_off, 1.0, 0.02) << depth;
  }
}
