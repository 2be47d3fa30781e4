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
  cv::Mat shaded = nested_drawing();
  rktest::add_shading(shaded, cv::Rect(250, 60, 110, 100));
  for (const auto& [name, img] : {std::pair{"clean", nested_drawing()}, std::pair{"shaded + noise + JPEG", rktest::paper_and_jpeg(shaded, 0.08, 40)}}) {
    const DrawingCurves c = extract_drawing_curves(img);
    const DrawingInterpretation d = interpret_drawing(c);
    const int paper = region_of(d, 5, 5), object = region_of(d, 300, 300), disc = region_of(d, 160, 160),
              ring = region_of(d, 420, 100), inner = region_of(d, 420, 170), left = region_of(d, 200, 410),
              right = region_of(d, 380, 410);
    for (int r : {paper, object, disc, ring, inner, left, right}) ASSERT_GE(r, 0) << name;
    std::printf("[drawing interpretation, %s] %zu curves, %d regions; levels: paper %d, object %d, disc %d, ring %d, "
                "inner disc %d, rectangle halves %d / %d\n",
                name, c.curves.size(), d.region_count, d.region_height[paper], d.region_height[object], d.region_height[disc],
                d.region_height[ring], d.region_height[inner], d.region_height[left], d.region_height[right]);
    const auto& h = d.region_height;
    EXPECT_EQ(h[paper], 0) << name;  // the paper is the ground
    EXPECT_EQ(h[object] - h[paper], 1) << name;
    EXPECT_EQ(h[disc] - h[object], 1) << name;
    EXPECT_EQ(h[ring] - h[object], 1) << name;
    EXPECT_EQ(h[inner] - h[ring], 1) << name;
    EXPECT_GE(std::min(h[left], h[right]) - h[object], 1) << name;
    EXPECT_EQ(std::abs(h[left] - h[right]), 1) << name;  // the dividing line is a step too (Constraint 1)
  }
}

namespace {
// The curve with region `r` on one of its sides and `other` on the other (any pair when other < 0).
int curve_between(const DrawingInterpretation& d, int r, int other = -1) {
  for (size_t i = 0; i < d.sides.size(); ++i)
    if ((d.sides[i][0] == r && (other < 0 || d.sides[i][1] == other)) || (d.sides[i][1] == r && (other < 0 || d.sides[i][0] == other)))
      return int(i);
  return -1;
}
CurveOverride lower_side(const DrawingInterpretation& d, int k, int lower_region) {
  CurveOverride o;
  o.curve = k;
  o.direction = d.sides[size_t(k)][0] == lower_region ? CurveOverride::Direction::LeftLower : CurveOverride::Direction::RightLower;
  return o;
}
}  // namespace

TEST(DrawingInterpretation, OverridesSinkRaiseAndFlatten) {
  const DrawingCurves c = extract_drawing_curves(nested_drawing());
  const DrawingInterpretation d = interpret_drawing(c);
  const int object = region_of(d, 300, 300), disc = region_of(d, 160, 160), ring = region_of(d, 420, 100),
            inner = region_of(d, 420, 170), left = region_of(d, 200, 410), right = region_of(d, 380, 410);
  const int k_inner = curve_between(d, inner), k_disc = curve_between(d, disc), k_split = curve_between(d, left, right);
  ASSERT_GE(k_inner, 0);
  ASSERT_GE(k_disc, 0);
  ASSERT_GE(k_split, 0);
  // Sunken: the inner disc below the ring (direction), the disc three levels up (weight).
  InterpretationParams p;
  p.overrides.push_back(lower_side(d, k_inner, inner));
  CurveOverride w;
  w.curve = k_disc, w.weight = 3;
  p.overrides.push_back(w);
  // The line across the rectangle as a ridge: both halves at one level.
  CurveOverride ridge;
  ridge.curve = k_split;
  ridge.spans.push_back({0, 1, CurveProfile::Ridge, {}});
  p.overrides.push_back(ridge);
  const DrawingInterpretation f = interpret_drawing(c, p);
  const auto& h = f.region_height;
  EXPECT_EQ(h[inner] - h[ring], -1);
  EXPECT_EQ(h[disc] - h[object], 3);
  EXPECT_EQ(h[left], h[right]);
  EXPECT_EQ(h[left] - h[object], 1);
  // Refused: the same curve twice, an unknown curve, a bad span or shape.
  InterpretationParams twice = p;
  twice.overrides.push_back(lower_side(d, k_inner, ring));
  EXPECT_THROW(interpret_drawing(c, twice), InputError);
  InterpretationParams unknown;
  unknown.overrides.push_back({int(c.curves.size()) + 5, CurveOverride::Direction::LeftLower});
  EXPECT_THROW(interpret_drawing(c, unknown), InputError);
  InterpretationParams bad_span;
  CurveOverride o;
  o.curve = k_disc;
  o.spans.push_back({0.6, 0.2, CurveProfile::Step, {}});
  bad_span.overrides.push_back(o);
  EXPECT_THROW(interpret_drawing(c, bad_span), InputError);
  bad_span.overrides[0].spans = {{0, 1, CurveProfile::Step, {Vec2(0.5, 0), Vec2(-0.5, 1)}}};
  EXPECT_THROW(interpret_drawing(c, bad_span), InputError);
}

namespace {
// A disc cut into three sectors by three rays from its centre (a junction of three curves).
cv::Mat three_sectors() {
  cv::Mat img(400, 400, CV_8UC1, cv::Scalar(255));
  cv::circle(img, {200, 200}, 150, cv::Scalar(0), 2, cv::LINE_AA);
  for (double a : {-90.0, 30.0, 150.0}) {
    const double r = a * 3.14159265358979 / 180;
    cv::line(img, {200, 200}, {int(200 + 150 * std::cos(r)), int(200 + 150 * std::sin(r))}, cv::Scalar(0), 2, cv::LINE_AA);
  }
  return img;
}
}  // namespace

TEST(DrawingInterpretation, ACycleOfDirectionsIsRefused) {
  const DrawingCurves c = extract_drawing_curves(three_sectors());
  const DrawingInterpretation d = interpret_drawing(c);
  const int s1 = region_of(d, 280, 150), s2 = region_of(d, 200, 300), s3 = region_of(d, 120, 150);
  ASSERT_GE(s1, 0);
  ASSERT_GE(s2, 0);
  ASSERT_GE(s3, 0);
  ASSERT_NE(s1, s2);
  ASSERT_NE(s2, s3);
  ASSERT_NE(s3, s1);
  const int k12 = curve_between(d, s1, s2), k23 = curve_between(d, s2, s3), k31 = curve_between(d, s3, s1);
  std::printf("[drawing interpretation, three sectors] %zu curves, %d regions; rays %d %d %d\n", c.curves.size(), d.region_count,
              k12, k23, k31);
  ASSERT_GE(k12, 0);
  ASSERT_GE(k23, 0);
  ASSERT_GE(k31, 0);
  // Two of the three fixed: fine (s1 < s2 < s3); the third closing the loop: a cycle.
  InterpretationParams p;
  p.overrides = {lower_side(d, k12, s1), lower_side(d, k23, s2)};
  const DrawingInterpretation ok = interpret_drawing(c, p);
  EXPECT_LT(ok.region_height[s1], ok.region_height[s2]);
  EXPECT_LT(ok.region_height[s2], ok.region_height[s3]);
  p.overrides.push_back(lower_side(d, k31, s3));
  EXPECT_THROW(interpret_drawing(c, p), InputError);
}

#include <nlohmann/json.hpp>

#include "reliefkit/drawing_file.h"

TEST(DrawingInterpretation, TheInterpretationFileRoundTrips) {
  const DrawingCurves c = extract_drawing_curves(nested_drawing());
  const DrawingInterpretation d = interpret_drawing(c);
  const std::string text = interpretation_to_json("nested.png", c, LineDetectionParams{}, d);
  EXPECT_TRUE(overrides_from_json(text, c).empty());  // as written: nothing overridden
  const int inner = region_of(d, 420, 170), ring = region_of(d, 420, 100);
  const int k = curve_between(d, inner);
  ASSERT_GE(k, 0);
  // The user's edit: that curve's direction (the inner disc lower), a ridge shape on another.
  const std::string dir = d.sides[size_t(k)][0] == inner ? "left-lower" : "right-lower";
  nlohmann::json j = nlohmann::json::parse(text);
  ASSERT_EQ(j["curves"][size_t(k)]["id"].get<int>(), k);
  j["curves"][size_t(k)]["direction"] = dir;
  const std::string edited = j.dump(1);
  const auto o = overrides_from_json(edited, c);
  ASSERT_EQ(o.size(), 1u);
  EXPECT_EQ(o[0].curve, k);
  InterpretationParams p;
  p.overrides = o;
  const DrawingInterpretation f = interpret_drawing(c, p);
  EXPECT_LT(f.region_height[inner], f.region_height[ring]);
  // Spans and free-form shapes are read.
  const std::string spans = R"({"format": "reliefkit-drawing-interpretation", "curves": [{"id": 0, "spans": [
      {"from": 0, "to": 0.5, "profile": "ridge"}, {"from": 0.5, "to": 1, "profile": "step", "shape": [[-1, 0], [0, 0.8], [1, 1]]}]}]})";
  const auto so = overrides_from_json(spans, c);
  ASSERT_EQ(so.size(), 1u);
  ASSERT_EQ(so[0].spans.size(), 2u);
  EXPECT_EQ(so[0].spans[0].profile, CurveProfile::Ridge);
  EXPECT_EQ(so[0].spans[1].shape.size(), 3u);
  // Refused with a message: not JSON, not ours, an unknown curve, another extraction's curve, a bad value.
  EXPECT_THROW(overrides_from_json("{not json", c), InputError);
  EXPECT_THROW(overrides_from_json(R"({"curves": []})", c), InputError);
  EXPECT_THROW(overrides_from_json(R"({"format": "reliefkit-drawing-interpretation", "curves": [{"id": 99}]})", c), InputError);
  EXPECT_THROW(overrides_from_json(R"({"format": "reliefkit-drawing-interpretation", "curves": [{"id": 0, "start": [1, 1], "end": [2, 2]}]})", c),
               InputError);
  EXPECT_THROW(overrides_from_json(R"({"format": "reliefkit-drawing-interpretation", "curves": [{"id": 0, "direction": "up"}]})", c),
               InputError);
  EXPECT_THROW(overrides_from_json(R"({"format": "reliefkit-drawing-interpretation", "curves": [{"id": 0, "weight": "high"}]})", c),
               InputError);
  EXPECT_THROW(overrides_from_json(R"({"format": "reliefkit-drawing-interpretation", "curves": [{"id": 0, "direction": 3}]})", c),
               InputError);
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
