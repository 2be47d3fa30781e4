#include "vessels.h"

#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>

namespace rktest {

using reliefkit::Vec2;

namespace {

constexpr double kRim = 60, kBase = 480, kWall = 14;

double outer_radius(double y) {
  const double u = (y - kRim) / (kBase - kRim);
  return 110 + 80 * std::sin(M_PI * 0.9 * u) - 30 * u;
}

// The true section in (radius, height): the outer wall down from `top`, the base (to the axis) or a
// break at `bottom`, the inner wall up, the rim or a break at `top`.
std::vector<Vec2> true_section(double top, double bottom, bool base) {
  std::vector<Vec2> s;
  for (double y = top; y <= bottom; y += 1) s.emplace_back(outer_radius(y), -y);
  if (base) {
    s.emplace_back(0, -kBase), s.emplace_back(0, -(kBase - kWall));
    for (double y = kBase - kWall; y >= top; y -= 1) s.emplace_back(outer_radius(y) - kWall, -y);
  } else {
    for (double y = bottom; y >= top; y -= 1) s.emplace_back(outer_radius(y) - kWall, -y);
  }
  return s;
}

std::vector<cv::Point> to_image(const std::vector<Vec2>& rh, double axis, bool left) {
  std::vector<cv::Point> out;
  for (const Vec2& q : rh) out.emplace_back(int(std::lround(axis + (left ? -1 : 1) * q.x())), int(std::lround(-q.y())));
  return out;
}

void draw_section(cv::Mat& img, const std::vector<cv::Point>& poly, const VesselDrawingOptions& o) {
  const std::vector<std::vector<cv::Point>> polys{poly};
  if (o.style == SectionStyle::Filled) {
    cv::fillPoly(img, polys, cv::Scalar(0), cv::LINE_AA);
    return;
  }
  if (o.style == SectionStyle::Hatched) {
    cv::Mat inside(img.size(), CV_8U, cv::Scalar(0)), hatch(img.size(), CV_8U, cv::Scalar(0));
    cv::fillPoly(inside, polys, cv::Scalar(255));
    for (int c = -img.rows; c < img.cols; c += 7) cv::line(hatch, {c, 0}, {c + img.rows, img.rows}, cv::Scalar(255), 1);
    img.setTo(0, hatch & inside);
  }
  cv::polylines(img, polys, true, cv::Scalar(0), o.line_px, cv::LINE_AA);
}

}  // namespace

VesselDrawing vessel_drawing(const VesselDrawingOptions& o) {
  VesselDrawing d;
  const double top = o.rim ? kRim : kRim + 60, bottom = o.base ? kBase : kBase - 80;
  d.height = bottom - top;
  d.section = true_section(top, bottom, o.base);
  d.image = cv::Mat(560, 640, CV_8UC1, cv::Scalar(255));
  std::vector<Vec2>& exterior = d.exterior;
  for (double y = top; y <= bottom; y += 1) exterior.emplace_back(outer_radius(y), -y);
  if (o.base) exterior.emplace_back(0, -kBase);
  for (const bool left : {true, false}) {
    if (left == o.section_left && o.style != SectionStyle::ProfileOnly) {
      draw_section(d.image, to_image(d.section, d.axis_x, left), o);
      continue;
    }
    cv::polylines(d.image, std::vector<std::vector<cv::Point>>{to_image(exterior, d.axis_x, left)}, false, cv::Scalar(0),
                  o.line_px, cv::LINE_AA);
  }
  const int mouth = int(std::lround(outer_radius(top)));
  if (o.rim) cv::line(d.image, cv::Point(int(d.axis_x) - mouth, int(top)), cv::Point(int(d.axis_x) + mouth, int(top)), cv::Scalar(0),
           o.line_px, cv::LINE_AA);
  if (o.axis_line) cv::line(d.image, cv::Point(int(d.axis_x), 30), cv::Point(int(d.axis_x), 520), cv::Scalar(0), 1);
  return d;
}

double distance_to_polygon(const Vec2& q, const std::vector<Vec2>& poly, bool closed) {
  double best = 1e300;
  for (size_t i = 0; i + (closed ? 0 : 1) < poly.size(); ++i) {
    const Vec2 a = poly[i], b = poly[(i + 1) % poly.size()], d = b - a;
    const double t = d.squaredNorm() > 0 ? std::clamp((q - a).dot(d) / d.squaredNorm(), 0.0, 1.0) : 0;
    best = std::min(best, (a + t * d - q).norm());
  }
  return best;
}

}  // namespace rktest
