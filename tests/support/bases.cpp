#include "bases.h"

#include <opencv2/imgproc.hpp>

namespace rktest {

using reliefkit::Outline;
using reliefkit::TriMesh;
using reliefkit::Vec2;
using reliefkit::Vec3;

TriMesh upright(const TriMesh& model, double yaw_degrees, bool mirror) {
  const double a = yaw_degrees * M_PI / 180, c = std::cos(a), s = std::sin(a);
  TriMesh out = model;
  for (auto& p : out.vertices) {
    const double x = c * p.x() - s * p.y(), y = s * p.x() + c * p.y();
    p = Vec3(mirror ? -x : x, p.z(), -y);
  }
  if (mirror)
    for (auto& f : out.faces) std::swap(f[1], f[2]);
  return out;
}

cv::Mat draw_figure(const Outline& outline, const FigureStyle& st, std::mt19937& rng, cv::Vec3d* to_px) {
  cv::Mat img(st.size, st.size, CV_8UC1, cv::Scalar(255));
  Vec2 lo = outline[0], hi = outline[0];
  for (const auto& p : outline) { lo = lo.cwiseMin(p); hi = hi.cwiseMax(p); }
  const double a = st.scale > 0 ? st.scale : 0.7 * st.size / std::max(hi.x() - lo.x(), hi.y() - lo.y());
  const double b = 0.5 * st.size - a * 0.5 * (lo.x() + hi.x()), c = 0.5 * st.size + a * 0.5 * (lo.y() + hi.y());
  if (to_px) *to_px = cv::Vec3d(a, b, c);
  const Outline px = outline_in_pixels(outline, cv::Vec3d(a, b, c));
  std::vector<cv::Point> poly;
  for (const auto& p : px) poly.emplace_back(int(std::lround(p.x())), int(std::lround(p.y())));
  if (st.hatching) {
    cv::Mat inside = cv::Mat::zeros(img.size(), CV_8U);
    cv::fillPoly(inside, std::vector<std::vector<cv::Point>>{poly}, cv::Scalar(255));
    cv::erode(inside, inside, cv::Mat(), cv::Point(-1, -1), 8);
    cv::Mat strokes(img.size(), CV_8U, cv::Scalar(255));
    for (int k = -st.size; k < st.size; k += 14) cv::line(strokes, {k, 0}, {k + st.size / 2, st.size}, cv::Scalar(60), 1);
    strokes.copyTo(img, inside);
  }
  cv::polylines(img, std::vector<std::vector<cv::Point>>{poly}, true, cv::Scalar(0), st.line, cv::LINE_AA);
  std::uniform_int_distribution<size_t> at(0, poly.size() - 1);
  for (int g = 0; g < st.gaps; ++g) cv::circle(img, poly[at(rng)], st.gap_px / 2, cv::Scalar(255), cv::FILLED);
  if (st.caption)
    cv::putText(img, "Fig. 12", {int(0.05 * st.size), int(0.97 * st.size)}, cv::FONT_HERSHEY_SIMPLEX, 0.8, cv::Scalar(0), 2);
  if (st.noise > 0) {
    cv::Mat n(img.size(), CV_32F);
    cv::randn(n, 0, 255 * st.noise);
    cv::Mat f;
    img.convertTo(f, CV_32F);
    f += n;
    f.convertTo(img, CV_8U);
  }
  return img;
}

cv::Mat draw_views(const TriMesh& model, const std::vector<reliefkit::ViewKind>& views, FigureStyle st, std::mt19937& rng) {
  std::vector<Outline> outlines;
  double extent = 0;
  for (auto v : views) {
    outlines.push_back(reliefkit::mesh_outline(model, v, 800));
    extent = std::max(extent, reliefkit::outline_diagonal(outlines.back()) / std::sqrt(2.0));
  }
  if (st.scale <= 0) st.scale = 0.75 * st.size / extent;
  std::vector<cv::Mat> tiles;
  for (size_t i = 0; i < views.size(); ++i) {
    FigureStyle s = st;
    s.caption = st.caption && i + 1 == views.size();
    tiles.push_back(draw_figure(outlines[i], s, rng));
  }
  cv::Mat out;
  cv::vconcat(tiles, out);
  return out;
}

Outline outline_in_pixels(const Outline& outline, const cv::Vec3d& t) {
  Outline px;
  for (const auto& p : outline) px.push_back(Vec2(t[0] * p.x() + t[1], -t[0] * p.y() + t[2]));
  return px;
}

Outline goblet_outline() {
  // Right half from the foot's edge up to the rim, (x, y); mirrored for the left half.
  const std::vector<Vec2> half = {{0.30, 0.00}, {0.30, 0.03}, {0.12, 0.06}, {0.05, 0.12}, {0.045, 0.40},
                                  {0.10, 0.45}, {0.25, 0.52}, {0.33, 0.65}, {0.36, 0.85}, {0.36, 1.00}};
  Outline o;
  for (size_t i = 0; i + 1 < half.size(); ++i)
    for (int k = 0; k < 10; ++k) o.push_back(half[i] + (half[i + 1] - half[i]) * (k / 10.0));
  o.push_back(half.back());
  const size_t n = o.size();
  for (size_t i = n; i-- > 0;) o.push_back(Vec2(-o[i].x(), o[i].y()));
  return o;
}

}  // namespace rktest
