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

// Sherds drawn inside the exterior half: closed outlines, each with a cross-hatched band.
void draw_sherds(cv::Mat& img, double axis) {
  for (const auto& [y0, y1] : {std::pair{120, 200}, std::pair{250, 330}}) {
    const std::vector<cv::Point> sherd{{int(axis) + 20, y0}, {int(axis) + int(outer_radius(y0)) - 25, y0 + 8},
                                       {int(axis) + int(outer_radius(y1)) - 25, y1}, {int(axis) + 30, y1 - 6}};
    cv::Mat inside(img.size(), CV_8U, cv::Scalar(0)), hatch(img.size(), CV_8U, cv::Scalar(0));
    cv::fillPoly(inside, std::vector<std::vector<cv::Point>>{sherd}, cv::Scalar(255));
    cv::rectangle(inside, cv::Point(0, 0), cv::Point(img.cols, y0 + 25), cv::Scalar(0), cv::FILLED);
    cv::rectangle(inside, cv::Point(0, y0 + 55), cv::Point(img.cols, img.rows), cv::Scalar(0), cv::FILLED);
    for (int c = -img.rows; c < img.cols; c += 6) {
      cv::line(hatch, {c, 0}, {c + img.rows, img.rows}, cv::Scalar(255), 1);
      cv::line(hatch, {c + img.rows, 0}, {c, img.rows}, cv::Scalar(255), 1);
    }
    img.setTo(0, hatch & inside);
    cv::polylines(img, std::vector<std::vector<cv::Point>>{sherd}, true, cv::Scalar(0), 2, cv::LINE_AA);
  }
}

// What a catalogue page adds round a vessel: a base section drawn apart below, a number to the
// right, a second, smaller vessel (filled section, outline, rim line, axis) further right.
void draw_catalogue_extras(cv::Mat& img, const VesselDrawingOptions& o, double axis) {
  if (o.base_drawn_apart) {
    const std::vector<cv::Point> base{{int(axis) - 150, 600}, {int(axis) - 10, 600}, {int(axis) - 10, 616}, {int(axis) - 150, 616}};
    cv::fillPoly(img, std::vector<std::vector<cv::Point>>{base}, cv::Scalar(0), cv::LINE_AA);
    cv::line(img, cv::Point(int(axis) + 10, 600), cv::Point(int(axis) + 150, 600), cv::Scalar(0), 2, cv::LINE_AA);
  }
  if (o.label_right > 0)
    cv::putText(img, "1042", cv::Point(int(axis) + 200 + o.label_right, 300), cv::FONT_HERSHEY_SIMPLEX, 1.2, cv::Scalar(0), 3);
  if (o.second_vessel > 0) {
    const int a = int(axis) + 200 + o.second_vessel;
    const std::vector<cv::Point> wall{{a - 90, 200}, {a - 70, 330}, {a - 60, 330}, {a - 80, 200}};
    cv::fillPoly(img, std::vector<std::vector<cv::Point>>{wall}, cv::Scalar(0), cv::LINE_AA);
    cv::line(img, cv::Point(a + 85, 200), cv::Point(a + 65, 330), cv::Scalar(0), 2, cv::LINE_AA);
    cv::line(img, cv::Point(a - 80, 200), cv::Point(a + 85, 200), cv::Scalar(0), 2, cv::LINE_AA);
    cv::line(img, cv::Point(a, 190), cv::Point(a, 340), cv::Scalar(0), 1);
  }
}

}  // namespace

VesselDrawing vessel_drawing(const VesselDrawingOptions& o) {
  VesselDrawing d;
  const double top = o.rim ? kRim : kRim + 60, bottom = o.base ? kBase : kBase - 80;
  d.height = bottom - top;
  d.section = true_section(top, bottom, o.base);
  const int wider = o.label_right > 0 || o.second_vessel > 0 ? 280 + o.label_right + o.second_vessel : 0;
  d.image = cv::Mat(o.base_drawn_apart ? 760 : 560, 640 + wider, CV_8UC1, cv::Scalar(255));
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
  if (o.decorated_sherds) draw_sherds(d.image, d.axis_x);  // on the exterior half (the section on the left)
  draw_catalogue_extras(d.image, o, d.axis_x);
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
