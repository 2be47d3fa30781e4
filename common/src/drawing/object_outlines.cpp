// The outlines of the drawn objects where no curve was found along them (issue 23, a plate of many
// objects): engravings draw an object's edge with the ends of its hatching, or with a line broken
// in places, so the curves alone leave the object open to the paper and it cannot rise.
#include <opencv2/imgproc.hpp>

#include <cmath>

#include "reliefkit/base/scale.h"
#include "reliefkit/drawing/line_drawing.h"

namespace reliefkit {

namespace {

// A stretch of an object's outline is added where it runs farther than this from every structure
// curve (px),
// when it is at least kMinOutlinePiece pixels long.
constexpr float kNearCurve = 2.0f;
constexpr size_t kMinOutlinePiece = 3;
// A stretch is carried on along the contour by at most this many pixels to touch the curve it meets.
constexpr int kMaxReachToCurve = 8;
// Objects smaller than this (px^2: dust, specks of a scan) get no outline.
constexpr int kMinObjectArea = 400;

// The objects (255 inside one): the ink, stippling and shading included, closed over gaps up to
// 2 x `radius`, its holes filled; objects smaller than kMinObjectArea (dust, specks) left out. Two
// objects drawn closer than the gap become one.
cv::Mat object_silhouettes(const cv::Mat& ink, double radius) {
  cv::Mat closed(ink.rows + 2, ink.cols + 2, CV_8U, cv::Scalar(0));  // a frame of paper around the image
  ink.copyTo(closed(cv::Rect(1, 1, ink.cols, ink.rows)));
  const int d = 2 * int(std::ceil(radius)) + 1;
  cv::morphologyEx(closed, closed, cv::MORPH_CLOSE, cv::getStructuringElement(cv::MORPH_ELLIPSE, cv::Size(d, d)));
  cv::floodFill(closed, cv::Point(0, 0), cv::Scalar(128));
  const cv::Mat inside = cv::Mat(closed != 128)(cv::Rect(1, 1, ink.cols, ink.rows));
  cv::Mat labels, stats, centroids, out(ink.size(), CV_8U, cv::Scalar(0));
  cv::connectedComponentsWithStats(inside, labels, stats, centroids, 8, CV_32S);
  for (int y = 0; y < ink.rows; ++y)
    for (int x = 0; x < ink.cols; ++x) {
      const int l = labels.at<int>(y, x);
      if (l > 0 && stats.at<int>(l, cv::CC_STAT_AREA) >= kMinObjectArea) out.at<uchar>(y, x) = 255;
    }
  return out;
}

// The stretches of a closed contour that run farther than `near` from every structure curve's
// centre line, each carried on along the contour until it reaches one (so that no gap is left where it meets
// it); the whole contour, closed, when it runs far from all of them.
std::vector<std::vector<Vec2>> far_stretches(const std::vector<cv::Point>& contour, const cv::Mat& dist, float near) {
  const long n = long(contour.size());
  auto at = [&](long i) { return contour[size_t(((i % n) + n) % n)]; };
  auto far = [&](long i) { return dist.at<float>(at(i)) > near; };
  auto touches = [&](long i) { return dist.at<float>(at(i)) <= 1.0f; };
  std::vector<std::vector<Vec2>> out;
  long start = 0;
  while (start < n && far(start)) ++start;
  if (start == n) {  // no curve near: the whole outline
    out.emplace_back();
    for (long i = 0; i <= n; ++i) out.back().emplace_back(at(i).x, at(i).y);
    return out;
  }
  for (long i = start; i < start + n;) {
    if (!far(i)) {
      ++i;
      continue;
    }
    long a = i, b = i;
    while (b + 1 < start + n && far(b + 1)) ++b;
    i = b + 1;
    if (b - a + 1 < long(kMinOutlinePiece)) continue;
    for (int k = 0; k < kMaxReachToCurve && !touches(a); ++k) --a;
    for (int k = 0; k < kMaxReachToCurve && !touches(b); ++k) ++b;
    out.emplace_back();
    for (long j = a; j <= b; ++j) out.back().emplace_back(at(j).x, at(j).y);
  }
  return out;
}

}  // namespace

int close_object_outlines(DrawingCurves& dc, const cv::Mat& ink, double radius, double stroke_width) {
  if (dc.curves.empty() || dc.width <= 0 || dc.height <= 0 || !(radius > 0)) return 0;
  if (ink.rows != dc.height || ink.cols != dc.width || ink.type() != CV_8U)
    throw InputError("close_object_outlines: the ink must be the drawing's (CV_8U, same size).");
  // Distance to the structure curves' centre lines (shading strokes bound no region).
  const cv::Mat silhouettes = object_silhouettes(ink, radius), dist = curve_distance(dc, dc.shading, false);
  dc.objects = silhouettes;
  // The contour runs along the ink's edge: half a stroke's width beside a curve that follows it.
  const float near = float(kNearCurve + 0.5 * stroke_width);
  std::vector<std::vector<cv::Point>> contours;
  cv::findContours(silhouettes, contours, cv::RETR_EXTERNAL, cv::CHAIN_APPROX_NONE);
  int added = 0;
  for (const auto& contour : contours)
    for (auto& piece : far_stretches(contour, dist, near)) {
      dc.curves.push_back(std::move(piece));
      dc.line_width.push_back(2.0);
      if (!dc.shading.empty()) dc.shading.push_back(0);
      ++added;
    }
  return added;
}

}  // namespace reliefkit
