#include "drawing_scores.h"

#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

namespace rktest {
namespace {

cv::Mat grey_of(const cv::Mat& drawing) {
  cv::Mat img = drawing;
  if (img.depth() == CV_16U) img.convertTo(img, CV_8U, 1 / 256.0);
  if (img.channels() == 4) {  // transparent counts as white paper
    std::vector<cv::Mat> ch;
    cv::split(img, ch);
    cv::Mat colour, white(img.size(), CV_8UC3, cv::Scalar::all(255)), alpha;
    cv::merge(std::vector<cv::Mat>{ch[0], ch[1], ch[2]}, colour);
    cv::cvtColor(ch[3], alpha, cv::COLOR_GRAY2BGR);
    alpha.convertTo(alpha, CV_32F, 1 / 255.0);
    cv::Mat c32, w32;
    colour.convertTo(c32, CV_32F);
    white.convertTo(w32, CV_32F);
    cv::Mat mixed = c32.mul(alpha) + w32.mul(cv::Scalar::all(1.0) - alpha);
    mixed.convertTo(img, CV_8UC3);
  }
  cv::Mat grey;
  if (img.channels() == 3) cv::cvtColor(img, grey, cv::COLOR_BGR2GRAY); else grey = img;
  return grey;
}

cv::Mat otsu_ink(const cv::Mat& drawing) {
  cv::Mat ink;
  cv::threshold(grey_of(drawing), ink, 0, 255, cv::THRESH_BINARY_INV | cv::THRESH_OTSU);
  return ink;
}

// The ink with its holes filled: everything not reached from the image's border through paper.
cv::Mat filled(const cv::Mat& ink) {
  cv::Mat outside = ~ink, padded;
  cv::copyMakeBorder(outside, padded, 1, 1, 1, 1, cv::BORDER_CONSTANT, 255);
  cv::floodFill(padded, cv::Point(0, 0), 128, nullptr, 0, 0, 4);
  return padded(cv::Rect(1, 1, ink.cols, ink.rows)) != 128;
}

double median_stroke_width(const cv::Mat& ink) {
  cv::Mat dist;
  cv::distanceTransform(ink, dist, cv::DIST_L2, cv::DIST_MASK_PRECISE);
  std::vector<float> ridge;
  for (int y = 1; y + 1 < dist.rows; ++y)
    for (int x = 1; x + 1 < dist.cols; ++x) {
      const float d = dist.at<float>(y, x);
      if (d <= 0) continue;
      bool top = true;
      for (int dy = -1; dy <= 1 && top; ++dy)
        for (int dx = -1; dx <= 1; ++dx) top = top && dist.at<float>(y + dy, x + dx) <= d;
      if (top) ridge.push_back(d);
    }
  if (ridge.empty()) return 1;
  std::nth_element(ridge.begin(), ridge.begin() + long(ridge.size() / 2), ridge.end());
  return std::max(1.0, 2.0 * ridge[ridge.size() / 2]);
}

double error_percentile(std::vector<double> v, double q) {
  if (v.empty()) return std::numeric_limits<double>::quiet_NaN();
  const size_t k = std::min(v.size() - 1, size_t(q * double(v.size())));
  std::nth_element(v.begin(), v.begin() + long(k), v.end());
  return v[k];
}

std::string pct(double share) {
  std::ostringstream o;
  o << std::lround(100 * share) << " %";
  return o.str();
}

// The relief's height rasterised at the drawing's pixel centres (NaN where it does not reach).
cv::Mat height_raster(const reliefkit::TriMesh& m, const std::vector<double>& h, double pixel_mm, cv::Size size) {
  cv::Mat out(size, CV_64F, cv::Scalar(std::numeric_limits<double>::quiet_NaN()));
  for (const auto& f : m.faces) {
    cv::Point2d p[3];
    double z[3];
    for (int k = 0; k < 3; ++k) {
      const auto& v = m.vertices[size_t(f[size_t(k)])];
      p[k] = {v.x() / pixel_mm, -v.y() / pixel_mm};
      z[k] = h[size_t(f[size_t(k)])];
    }
    const double det = (p[1].x - p[0].x) * (p[2].y - p[0].y) - (p[2].x - p[0].x) * (p[1].y - p[0].y);
    if (std::abs(det) < 1e-12) continue;
    const int x0 = std::max(0, int(std::ceil(std::min({p[0].x, p[1].x, p[2].x}))));
    const int x1 = std::min(size.width - 1, int(std::floor(std::max({p[0].x, p[1].x, p[2].x}))));
    const int y0 = std::max(0, int(std::ceil(std::min({p[0].y, p[1].y, p[2].y}))));
    const int y1 = std::min(size.height - 1, int(std::floor(std::max({p[0].y, p[1].y, p[2].y}))));
    for (int y = y0; y <= y1; ++y)
      for (int x = x0; x <= x1; ++x) {
        const double b1 = ((x - p[0].x) * (p[2].y - p[0].y) - (p[2].x - p[0].x) * (y - p[0].y)) / det;
        const double b2 = ((p[1].x - p[0].x) * (y - p[0].y) - (x - p[0].x) * (p[1].y - p[0].y)) / det;
        const double b0 = 1 - b1 - b2;
        if (b0 < -1e-9 || b1 < -1e-9 || b2 < -1e-9) continue;
        out.at<double>(y, x) = b0 * z[0] + b1 * z[1] + b2 * z[2];
      }
  }
  return out;
}

}  // namespace

DrawnObjects drawn_objects(const cv::Mat& drawing, double min_share) {
  DrawnObjects o;
  o.ink = otsu_ink(drawing);
  o.pen = median_stroke_width(o.ink);
  cv::Mat closed, stats, centroids;
  cv::morphologyEx(o.ink, closed, cv::MORPH_CLOSE, cv::getStructuringElement(cv::MORPH_ELLIPSE, {3, 3}));
  const int n = cv::connectedComponentsWithStats(filled(closed), o.labels, stats, centroids, 8, CV_32S);
  int largest = 0;
  for (int l = 1; l < n; ++l) largest = std::max(largest, stats.at<int>(l, cv::CC_STAT_AREA));
  std::vector<int> renamed(size_t(n), -1);
  renamed[0] = 0;
  for (int l = 1; l < n; ++l)
    if (stats.at<int>(l, cv::CC_STAT_AREA) >= min_share * largest) renamed[size_t(l)] = ++o.count;
  for (int y = 0; y < o.labels.rows; ++y)
    for (int x = 0; x < o.labels.cols; ++x) o.labels.at<int>(y, x) = renamed[size_t(o.labels.at<int>(y, x))];
  return o;
}

namespace {

// Pixels at least `band` from every other label (the relief steps within a few px of each line).
cv::Mat away_from_boundary(const cv::Mat& labels, int label, double band) {
  cv::Mat other = labels != label, dist;
  cv::distanceTransform(~other, dist, cv::DIST_L2, cv::DIST_MASK_PRECISE);  // distance to `other`
  return dist >= band;
}

void judge_relief(ReliefScore& s) {
  std::ostringstream cause;
  for (size_t k = 0; k < s.raised.size(); ++k)
    if (s.raised[k] < 0.9) cause << "object " << k + 1 << " of " << s.objects << " " << pct(s.raised[k]) << " raised; ";
  if (s.objects == 0) cause << "no closed object in the drawing; ";
  if (s.paper_flat < 0.95) cause << "paper " << pct(s.paper_flat) << " flat; ";
  if (s.below_paper > 0.005) cause << pct(s.below_paper) << " below the paper; ";
  s.cause = cause.str();
  if (!s.cause.empty()) s.cause.resize(s.cause.size() - 2);
  s.pass = s.cause.empty();
}

}  // namespace

ReliefScore score_relief(const cv::Mat& drawing, const reliefkit::TriMesh& relief, const std::vector<double>& height,
                         double pixel_mm, double step_share) {
  ReliefScore s;
  const DrawnObjects o = drawn_objects(drawing);
  s.objects = o.count;
  double x0 = 1e300, x1 = -1e300;
  for (const auto& v : relief.vertices) x0 = std::min(x0, v.x()), x1 = std::max(x1, v.x());
  s.step = step_share * (x1 - x0);
  const cv::Mat h = height_raster(relief, height, pixel_mm, drawing.size());
  const double band = 0.5 * o.pen + 6;  // the step's half-width (4 px) and a little
  std::vector<long> inside(size_t(o.count) + 1, 0), raised(size_t(o.count) + 1, 0);
  long uncovered = 0, paper = 0, flat = 0, covered = 0, below = 0;
  cv::Mat labels_no_small = o.labels.clone();
  labels_no_small.setTo(0, o.labels < 0);
  const cv::Mat paper_far = away_from_boundary(o.labels, 0, band);
  for (int k = 1; k <= o.count; ++k) {
    const cv::Mat interior = away_from_boundary(o.labels, k, band);
    for (int y = 0; y < h.rows; ++y)
      for (int x = 0; x < h.cols; ++x) {
        if (!interior.at<uchar>(y, x) || o.labels.at<int>(y, x) != k) continue;
        const double z = h.at<double>(y, x);
        ++inside[size_t(k)];
        if (std::isnan(z)) ++uncovered; else raised[size_t(k)] += z >= 0.5 * s.step;
      }
  }
  for (int y = 0; y < h.rows; ++y)
    for (int x = 0; x < h.cols; ++x) {
      const double z = h.at<double>(y, x);
      if (std::isnan(z)) continue;
      ++covered, below += z < -0.25 * s.step;
      if (o.labels.at<int>(y, x) == 0 && paper_far.at<uchar>(y, x)) ++paper, flat += std::abs(z) <= 0.25 * s.step;
    }
  long all_inside = 0;
  for (int k = 1; k <= o.count; ++k) {
    s.raised.push_back(inside[size_t(k)] ? double(raised[size_t(k)]) / double(inside[size_t(k)]) : 1.0);
    all_inside += inside[size_t(k)];
  }
  s.paper_flat = paper ? double(flat) / double(paper) : 1.0;
  s.below_paper = covered ? double(below) / double(covered) : 0.0;
  s.uncovered = all_inside ? double(uncovered) / double(all_inside) : 0.0;
  judge_relief(s);
  return s;
}

VesselFrame vessel_frame(const reliefkit::TriMesh& m, double pixel_mm, int rows) {
  VesselFrame f;
  double lo[2] = {1e300, 1e300}, hi[2] = {-1e300, -1e300};
  for (const auto& v : m.vertices) {
    lo[0] = std::min(lo[0], v.x()), hi[0] = std::max(hi[0], v.x());
    lo[1] = std::min(lo[1], v.z()), hi[1] = std::max(hi[1], v.z());
  }
  f.axis_x = 0.5 * (lo[0] + hi[0]), f.axis_z = 0.5 * (lo[1] + hi[1]);
  f.radius.assign(size_t(rows), std::numeric_limits<double>::quiet_NaN());
  auto mark = [&](const reliefkit::Vec3& a, const reliefkit::Vec3& b) {
    const double pa = -a.y() / pixel_mm, pb = -b.y() / pixel_mm;
    const int r0 = std::max(0, int(std::ceil(std::min(pa, pb)))), r1 = std::min(rows - 1, int(std::floor(std::max(pa, pb))));
    for (int r = r0; r <= r1; ++r) {
      const double t = pa == pb ? 0 : (r - pa) / (pb - pa);
      const reliefkit::Vec3 q = a + (b - a) * t;
      const double radius = std::hypot(q.x() - f.axis_x, q.z() - f.axis_z) / pixel_mm;
      double& best = f.radius[size_t(r)];
      if (std::isnan(best) || radius > best) best = radius;
    }
  };
  for (const auto& t : m.faces)
    for (int k = 0; k < 3; ++k) mark(m.vertices[size_t(t[size_t(k)])], m.vertices[size_t(t[size_t((k + 1) % 3)])]);
  return f;
}

namespace {

// The pieces of the drawing the vessel was made from: the connected ink (closed over 3 px) with at
// least half of it within the vessel's extent (grown by a tenth), each whole.
cv::Mat vessel_piece(const cv::Mat& ink, const VesselFrame& f, double pixel_mm) {
  double rmax = 0;
  int top = -1, bottom = -1;
  for (size_t r = 0; r < f.radius.size(); ++r)
    if (!std::isnan(f.radius[r])) rmax = std::max(rmax, f.radius[r]), bottom = int(r), top = top < 0 ? int(r) : top;
  if (top < 0) return cv::Mat::zeros(ink.size(), CV_8U);
  const double ax = f.axis_x / pixel_mm, grow_x = 0.2 * rmax, grow_y = 0.1 * (bottom - top);
  const cv::Rect box = cv::Rect(int(ax - rmax - grow_x), int(top - grow_y), int(2 * (rmax + grow_x)) + 1,
                                int(bottom - top + 2 * grow_y) + 1) & cv::Rect(0, 0, ink.cols, ink.rows);
  cv::Mat closed, labels;
  cv::morphologyEx(ink, closed, cv::MORPH_CLOSE, cv::getStructuringElement(cv::MORPH_ELLIPSE, {7, 7}));
  const int n = cv::connectedComponents(closed, labels, 8, CV_32S);
  std::vector<long> inside(size_t(n), 0), all(size_t(n), 0);
  for (int y = 0; y < ink.rows; ++y)
    for (int x = 0; x < ink.cols; ++x)
      if (ink.at<uchar>(y, x)) ++all[size_t(labels.at<int>(y, x))], inside[size_t(labels.at<int>(y, x))] += box.contains({x, y});
  cv::Mat piece(ink.size(), CV_8U, cv::Scalar(0));
  for (int y = 0; y < ink.rows; ++y)
    for (int x = 0; x < ink.cols; ++x) {
      const int l = labels.at<int>(y, x);
      if (l > 0 && ink.at<uchar>(y, x) && 2 * inside[size_t(l)] >= all[size_t(l)]) piece.at<uchar>(y, x) = 255;
    }
  return piece;
}

// The drawing's own axis: the most common midpoint of a row's outer edges (rows wider than four
// pens), within a window of two pens or 1 % of the widest row.
double mirror_line(const std::vector<int>& left, const std::vector<int>& right, double pen, int widest, int cols) {
  std::vector<double> count(size_t(2 * cols), 0);
  for (size_t y = 0; y < left.size(); ++y)
    if (left[y] >= 0 && right[y] - left[y] >= 4 * pen) count[size_t(left[y] + right[y])] += 1;
  const int window = int(std::ceil(2 * std::max(2 * pen, 0.01 * widest)));
  std::vector<double> prefix(count.size() + 1, 0);
  for (size_t k = 0; k < count.size(); ++k) prefix[k + 1] = prefix[k] + count[k];
  size_t mode = 0;
  double best = -1;
  for (size_t b = 0; b < count.size(); ++b) {
    const size_t lo = b >= size_t(window) ? b - size_t(window) : 0, hi = std::min(count.size(), b + size_t(window) + 1);
    if (prefix[hi] - prefix[lo] > best) best = prefix[hi] - prefix[lo], mode = b;
  }
  double weighted = 0, total = 0;
  for (size_t k = mode >= size_t(window) ? mode - size_t(window) : 0; k < std::min(count.size(), mode + size_t(window) + 1); ++k)
    weighted += double(k) * count[k], total += count[k];
  return 0.5 * (total > 0 ? weighted / total : double(mode));
}

}  // namespace

VesselScore score_vessel(const cv::Mat& drawing, const reliefkit::TriMesh& vessel, double pixel_mm) {
  VesselScore s;
  const cv::Mat ink = otsu_ink(drawing);
  const double pen = median_stroke_width(ink);
  const VesselFrame f = vessel_frame(vessel, pixel_mm, drawing.rows);
  s.vessel_axis = f.axis_x / pixel_mm;
  const cv::Mat piece = vessel_piece(ink, f, pixel_mm);
  std::vector<int> left(size_t(piece.rows), -1), right(size_t(piece.rows), -1);
  int widest = 0;
  for (int y = 0; y < piece.rows; ++y) {
    const uchar* row = piece.ptr<uchar>(y);
    for (int x = 0; x < piece.cols; ++x)
      if (row[x]) { if (left[size_t(y)] < 0) left[size_t(y)] = x; right[size_t(y)] = x; }
    if (left[size_t(y)] >= 0) widest = std::max(widest, right[size_t(y)] - left[size_t(y)]);
  }
  if (widest == 0) {
    s.cause = "no drawing where the vessel is";
    return s;
  }
  s.drawn_axis = mirror_line(left, right, pen, widest, piece.cols);
  const double half_widest = 0.5 * widest;
  long covered = 0;
  std::vector<double> errors;
  for (int y = 0; y < piece.rows; ++y) {
    if (left[size_t(y)] < 0) continue;
    const double l = s.drawn_axis - left[size_t(y)], r = right[size_t(y)] - s.drawn_axis;
    if (l < 0.1 * half_widest || r < 0.1 * half_widest || std::abs(l - r) > 0.1 * std::max(l, r)) continue;
    const double drawn = 0.5 * (right[size_t(y)] - left[size_t(y)] - pen);
    ++s.rows;
    const double radius = f.radius[size_t(y)];
    if (std::isnan(radius)) continue;
    ++covered;
    errors.push_back(std::abs(radius - drawn) / drawn);
  }
  s.coverage = s.rows ? double(covered) / double(s.rows) : 0;
  s.median_error = error_percentile(errors, 0.5);
  s.p90_error = error_percentile(errors, 0.9);
  std::ostringstream cause;
  if (s.rows == 0) cause << "no row where both sides are drawn; ";
  else if (s.coverage < 0.9) cause << "covers " << pct(s.coverage) << " of the drawn profile; ";
  if (!errors.empty() && s.median_error > 0.02) cause << "radius off by " << pct(s.median_error) << " (median); ";
  if (!errors.empty() && s.p90_error > 0.05) cause << "radius off by " << pct(s.p90_error) << " (90th percentile); ";
  s.cause = cause.str();
  if (!s.cause.empty()) s.cause.resize(s.cause.size() - 2);
  s.pass = s.cause.empty();
  return s;
}

}  // namespace rktest
