#include "reliefkit/drawing/shading.h"

#include <opencv2/imgproc.hpp>

#include <cmath>

#include "reliefkit/base/scale.h"

namespace reliefkit {

void ShadingParams::validate() const {
  require_range(max_angle, "Shading: parallel angle (radians)", 0, 1.6);
  require_range(max_spacing_widths, "Shading: spacing (line widths)", 0, 1000);
  require_range(min_spacing_px, "Shading: spacing (px)", 0, 1e6);
  require_range(min_hatched_share, "Shading: hatched share", 0, 1);
  if (min_family < 2) throw InputError("Shading: a family needs at least two lines.");
}

namespace {

// The ink and the direction of its lines: per pixel the angle (modulo pi) across the dominant
// gradient of the structure tensor, and how clearly one direction dominates (coherence, 0-1).
struct InkLines {
  cv::Mat ink;        // CV_8U, 255 on ink
  cv::Mat direction;  // CV_32F, radians in [0, pi)
  cv::Mat coherence;  // CV_32F
};

// Least coherence for a pixel's direction to be read (at a crossing no direction dominates).
constexpr double kMinCoherence = 0.5;

InkLines ink_lines(const cv::Mat& grey, const cv::Mat& ink) {
  InkLines out{ink, cv::Mat(), cv::Mat()};
  cv::Mat smooth, gx, gy;
  cv::GaussianBlur(grey, smooth, cv::Size(), 1.0);
  cv::Sobel(smooth, gx, CV_32F, 1, 0, 3);
  cv::Sobel(smooth, gy, CV_32F, 0, 1, 3);
  cv::Mat jxx = gx.mul(gx), jyy = gy.mul(gy), jxy = gx.mul(gy);
  for (cv::Mat* j : {&jxx, &jyy, &jxy}) cv::GaussianBlur(*j, *j, cv::Size(), 2.0);
  out.direction.create(grey.size(), CV_32F);
  out.coherence.create(grey.size(), CV_32F);
  for (int y = 0; y < grey.rows; ++y)
    for (int x = 0; x < grey.cols; ++x) {
      const float a = jxx.at<float>(y, x), b = jyy.at<float>(y, x), c = jxy.at<float>(y, x);
      double line = 0.5 * std::atan2(2.0 * c, double(a - b)) + M_PI / 2;  // across the gradient
      if (line >= M_PI) line -= M_PI;
      if (line < 0) line += M_PI;
      out.direction.at<float>(y, x) = float(line);
      out.coherence.at<float>(y, x) = float(std::hypot(double(a - b), 2.0 * c) / (a + b + 1e-12));
    }
  return out;
}

double angle_between(double a, double b) {
  const double d = std::abs(a - b);
  return std::min(d, M_PI - d);
}

// From p across a stroke of direction `angle`, along `dir`: how many lines of that direction follow
// one another, each within `reach` px of the last (the stroke's own ink first crossed; lines of
// another direction, or none readable, looked through). At most `enough`.
int parallel_lines(const InkLines& il, const Vec2& p, const Vec2& dir, double angle, double reach, double max_angle,
                   int enough) {
  int found = 0;
  double last = 0;  // where the last parallel line (or the stroke itself) was left
  bool in_ink = true, in_parallel = false;
  for (double s = 0.75; s <= last + reach && found < enough; s += 0.75) {
    const Vec2 q = p + s * dir;
    const int x = int(std::lround(q.x())), y = int(std::lround(q.y()));
    if (x < 0 || y < 0 || x >= il.ink.cols || y >= il.ink.rows) break;
    const bool ink = il.ink.at<uchar>(y, x) != 0;
    if (ink && !in_ink) {  // a line begins
      in_parallel = il.coherence.at<float>(y, x) >= kMinCoherence &&
                    angle_between(il.direction.at<float>(y, x), angle) <= max_angle;
      if (in_parallel) ++found;
    }
    if (!ink && in_ink && (in_parallel || found == 0)) last = s;  // left the stroke or a parallel line
    in_ink = ink;
  }
  return found;
}

double length_of(const std::vector<Vec2>& c) {
  double len = 0;
  for (size_t i = 1; i < c.size(); ++i) len += (c[i] - c[i - 1]).norm();
  return len;
}

bool is_closed(const std::vector<Vec2>& c) { return c.size() > 3 && (c.front() - c.back()).norm() <= 3; }

// Paper at p: no pixel within 1 px darker than the detector's darkest paper (max_intensity 0.75).
bool on_paper(const cv::Mat& grey, const Vec2& p) {
  const int x0 = int(std::lround(p.x())), y0 = int(std::lround(p.y()));
  for (int y = std::max(0, y0 - 1); y <= std::min(grey.rows - 1, y0 + 1); ++y)
    for (int x = std::max(0, x0 - 1); x <= std::min(grey.cols - 1, x0 + 1); ++x)
      if (grey.at<float>(y, x) < 0.75f) return false;
  return true;
}

// The share of curve k's samples (every 2 px) that lie in a family of at least min_family parallel
// lines, the stroke's own line counted, or on the paper (a stroke found between the crossings of a
// cross-hatching, where the smoothed image holds dark blobs but no line was drawn).
double hatched_share(const cv::Mat& grey, const InkLines& il, const DrawingCurves& dc, size_t k, const ShadingParams& p) {
  const auto& c = dc.curves[k];
  const double len = length_of(c);
  if (is_closed(c) || !(len > 0)) return 0;
  const double width = k < dc.line_width.size() ? dc.line_width[k] : 2.0;
  const double reach = std::min(len, std::max(p.min_spacing_px, p.max_spacing_widths * width));
  int samples = 0, hatched = 0;
  double next = 0, run = 0;
  for (size_t i = 1; i < c.size(); ++i) {
    const Vec2 d = c[i] - c[i - 1];
    const double seg = d.norm();
    for (; seg > 0 && next <= run + seg; next += 2) {
      const Vec2 t = d / seg, n(-t.y(), t.x());
      const Vec2 at = c[i - 1] + (next - run) * t;
      double angle = std::atan2(t.y(), t.x());
      if (angle < 0) angle += M_PI;
      ++samples;
      if (on_paper(grey, at)) {
        ++hatched;
        continue;
      }
      const int need = p.min_family - 1;
      const int one = parallel_lines(il, at, n, angle, reach, p.max_angle, need);
      const int lines = one + (one < need ? parallel_lines(il, at, -n, angle, reach, p.max_angle, need - one) : 0);
      hatched += lines >= need;
    }
    run += seg;
  }
  return samples > 0 ? double(hatched) / samples : 0;
}

}  // namespace

std::vector<char> shading_strokes(const cv::Mat& grey, const cv::Mat& ink, const DrawingCurves& dc, const ShadingParams& p) {
  p.validate();
  const int nc = int(dc.curves.size());
  std::vector<char> shading(static_cast<size_t>(nc), 0);
  if (nc == 0 || grey.empty()) return shading;
  const InkLines il = ink_lines(grey, ink);
#pragma omp parallel for schedule(dynamic, 16)
  for (int k = 0; k < nc; ++k) shading[size_t(k)] = hatched_share(grey, il, dc, size_t(k), p) >= p.min_hatched_share;
  return shading;
}

}  // namespace reliefkit
