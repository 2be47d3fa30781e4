// Dashed lines joined into lines (join_dashes): a drawing's reconstructed or hidden outline.

#include <Eigen/Eigenvalues>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>
#include <vector>

#include "reliefkit/drawing/line_drawing.h"

namespace reliefkit {

namespace {

// A stroke's extent along its principal direction and across it, from its pixels.
struct StrokeShape {
  Vec2 centre = Vec2::Zero(), direction = Vec2::UnitX();
  double length = 0, width = 0;
};

StrokeShape shape_of(const std::vector<Vec2>& pixels) {
  StrokeShape s;
  for (const Vec2& q : pixels) s.centre += q;
  s.centre /= double(pixels.size());
  Eigen::Matrix2d cov = Eigen::Matrix2d::Zero();
  for (const Vec2& q : pixels) cov += (q - s.centre) * (q - s.centre).transpose();
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eig(cov);
  s.direction = eig.eigenvectors().col(1);
  double lo = 0, hi = 0, across_lo = 0, across_hi = 0;
  const Vec2 normal(-s.direction.y(), s.direction.x());
  for (const Vec2& q : pixels) {
    const double t = (q - s.centre).dot(s.direction), u = (q - s.centre).dot(normal);
    lo = std::min(lo, t), hi = std::max(hi, t), across_lo = std::min(across_lo, u), across_hi = std::max(across_hi, u);
  }
  s.length = hi - lo + 1, s.width = across_hi - across_lo + 1;
  return s;
}

// The mean of a stroke's pixels within one pixel of its end in `direction` (+1 or -1 along it).
Vec2 end_of(const std::vector<Vec2>& pixels, const StrokeShape& s, double sign) {
  double far = -1e30;
  for (const Vec2& q : pixels) far = std::max(far, sign * (q - s.centre).dot(s.direction));
  Vec2 sum = Vec2::Zero();
  int n = 0;
  for (const Vec2& q : pixels)
    if (sign * (q - s.centre).dot(s.direction) >= far - 1) sum += q, ++n;
  return sum / double(n);
}

// The direction of the stroke through `at` (an ink pixel), unsigned: of its pixels within `steps`
// (8-connected) of it, so that a line running beside it does not count.
Vec2 local_direction(const cv::Mat& ink, cv::Point at, int steps) {
  const cv::Rect window = cv::Rect(at.x - steps, at.y - steps, 2 * steps + 1, 2 * steps + 1) & cv::Rect(0, 0, ink.cols, ink.rows);
  cv::Mat visited = cv::Mat::zeros(window.size(), CV_8U);  // the pixels `steps` can reach, not the image
  std::vector<cv::Point> front{at}, next;
  std::vector<Vec2> seen{Vec2(at.x, at.y)};
  visited.at<uchar>(at - window.tl()) = 1;
  for (int step = 0; step < steps && !front.empty(); ++step, front.swap(next)) {
    next.clear();
    for (const cv::Point& q : front)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          const cv::Point r(q.x + dx, q.y + dy);
          if (!window.contains(r) || visited.at<uchar>(r - window.tl()) || !ink.at<uchar>(r)) continue;
          visited.at<uchar>(r - window.tl()) = 1, next.push_back(r), seen.emplace_back(r.x, r.y);
        }
  }
  return seen.size() < 3 ? Vec2::Zero() : shape_of(seen).direction;
}

constexpr double kDashAspect = 2.5;     // a dash is at least this many times as long as it is wide
constexpr double kDashReach = 2.0;      // a gap is at most this many dash lengths
constexpr double kMaxDashTurn = 25.0;   // degrees between a dash's direction and the way to its partner
constexpr double kMaxStrokeTurn = 30.0; // degrees between the way from the dash and its partner's direction

// The drawing's strokes: each one's pixels and shape, and whether it is a dash.
struct Strokes {
  cv::Mat labels;
  std::vector<std::vector<Vec2>> pixels;
  std::vector<StrokeShape> shape;
  std::vector<char> dash;
  double typical_dash = 0;  // the median dash length (a line's last dash may be cut short)
};

Strokes strokes_of(const cv::Mat& ink, double pen, double max_length) {
  Strokes st;
  cv::Mat stats, centroids;
  const size_t n = size_t(cv::connectedComponentsWithStats(ink, st.labels, stats, centroids, 8, CV_32S));
  st.pixels.resize(n), st.shape.resize(n), st.dash.assign(n, 0);
  for (int y = 0; y < st.labels.rows; ++y)
    for (int x = 0; x < st.labels.cols; ++x)
      if (int l = st.labels.at<int>(y, x)) st.pixels[size_t(l)].emplace_back(x, y);
  std::vector<double> lengths;
  for (size_t l = 1; l < n; ++l) {
    const StrokeShape s = st.shape[l] = shape_of(st.pixels[l]);
    st.dash[l] = s.length <= max_length && s.length >= kDashAspect * std::max(s.width, pen);
    if (st.dash[l]) lengths.push_back(s.length);
  }
  if (lengths.empty()) return st;
  std::nth_element(lengths.begin(), lengths.begin() + long(lengths.size() / 2), lengths.end());
  st.typical_dash = lengths[lengths.size() / 2];
  return st;
}

// The ink of other strokes ahead of a dash's end (within `reach`, kMaxDashTurn of `ahead`), nearest first.
std::vector<std::pair<double, cv::Point>> ink_ahead(const Strokes& st, int label, const Vec2& end, const Vec2& ahead,
                                                    double reach) {
  const double cos_turn = std::cos(kMaxDashTurn * M_PI / 180);
  const int r = int(std::ceil(reach));
  std::vector<std::pair<double, cv::Point>> found;
  for (int y = std::max(0, int(end.y()) - r); y <= std::min(st.labels.rows - 1, int(end.y()) + r); ++y)
    for (int x = std::max(0, int(end.x()) - r); x <= std::min(st.labels.cols - 1, int(end.x()) + r); ++x) {
      const int other = st.labels.at<int>(y, x);
      const Vec2 v = Vec2(x, y) - end;
      const double d = v.norm();
      if (other != 0 && other != label && d <= reach && v.dot(ahead) >= cos_turn * d) found.emplace_back(d, cv::Point(x, y));
    }
  std::sort(found.begin(), found.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  return found;
}

// Whether the stroke at `q` runs along the way to it from `end` (kMaxStrokeTurn): the dash's line
// goes on there, not a stroke crossing it, a line beside it or a letter.
bool continues_line(const cv::Mat& ink, const Strokes& st, const Vec2& end, cv::Point q, double steps) {
  const int other = st.labels.at<int>(q);
  const Vec2 along = st.dash[size_t(other)] ? st.shape[size_t(other)].direction : local_direction(ink, q, int(std::ceil(steps)));
  return std::abs(along.dot((Vec2(q.x, q.y) - end).normalized())) >= std::cos(kMaxStrokeTurn * M_PI / 180);
}

constexpr int kMaxPartnersTried = 6;  // the nearest inks ahead (a pen apart) tried as a dash's partner

}  // namespace

int join_dashes(cv::Mat& ink, double pen, double max_length) {
  const Strokes st = strokes_of(ink, pen, max_length);
  std::vector<std::pair<cv::Point, cv::Point>> joins;
  for (size_t l = 1; l < st.dash.size(); ++l) {
    if (!st.dash[l]) continue;
    const StrokeShape& s = st.shape[l];
    const double reach = std::max(kDashReach * std::max(s.length, st.typical_dash), 4 * pen);
    for (double sign : {-1.0, 1.0}) {
      const Vec2 end = end_of(st.pixels[l], s, sign);
      std::vector<cv::Point> tried;
      for (const auto& found : ink_ahead(st, int(l), end, sign * s.direction, reach)) {
        const cv::Point q = found.second;  // (a structured binding cannot be captured in C++17)
        if (int(tried.size()) == kMaxPartnersTried) break;
        if (std::any_of(tried.begin(), tried.end(), [&](cv::Point t) { return cv::norm(t - q) < pen + 1; })) continue;
        tried.push_back(q);
        if (!continues_line(ink, st, end, q, s.length)) continue;
        joins.emplace_back(cv::Point(int(std::lround(end.x())), int(std::lround(end.y()))), q);
        break;
      }
    }
  }
  const int thickness = std::max(1, int(std::lround(pen)));
  for (const auto& j : joins) cv::line(ink, j.first, j.second, cv::Scalar(255), thickness, cv::LINE_8);
  return int(joins.size());
}

}  // namespace reliefkit
