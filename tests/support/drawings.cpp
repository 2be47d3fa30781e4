#include "drawings.h"

#include <opencv2/imgproc.hpp>

#include <cmath>

namespace rktest {

namespace {
cv::Point at(double scale, int x, int y) { return {int(std::lround(x * scale)), int(std::lround(y * scale))}; }
int len(double scale, int r) { return int(std::lround(r * scale)); }
}  // namespace

cv::Mat nested_drawing(double s, int line_px) {
  cv::Mat img(len(s, 600), len(s, 600), CV_8UC1, cv::Scalar(255));
  cv::rectangle(img, at(s, 40, 40), at(s, 560, 560), cv::Scalar(0), line_px, cv::LINE_AA);
  cv::circle(img, at(s, 160, 160), len(s, 70), cv::Scalar(0), line_px, cv::LINE_AA);
  cv::circle(img, at(s, 420, 170), len(s, 90), cv::Scalar(0), line_px, cv::LINE_AA);
  cv::circle(img, at(s, 420, 170), len(s, 40), cv::Scalar(0), line_px, cv::LINE_AA);
  cv::rectangle(img, at(s, 120, 340), at(s, 460, 480), cv::Scalar(0), line_px, cv::LINE_AA);
  cv::line(img, at(s, 290, 340), at(s, 290, 480), cv::Scalar(0), line_px, cv::LINE_AA);
  return img;
}

NestedParts nested_parts(double s) {
  return {at(s, 300, 300), at(s, 160, 160), at(s, 420, 100), at(s, 420, 170), at(s, 200, 410), at(s, 380, 410)};
}

LevelFit fit_levels(const reliefkit::TriMesh& grid, double pixel_size, const reliefkit::DrawingRelief& r,
                    const reliefkit::DrawingInterpretation& d, cv::Point paper) {
  LevelFit f;
  const int paper_region = d.regions.at<int>(paper.y, paper.x);
  double num = 0, den = 0;
  std::vector<std::pair<double, double>> pairs;  // (level, height)
  for (int v = 0; v < grid.n_vertices(); ++v) {
    const int x = int(std::lround(grid.vertices[v].x() / pixel_size)), y = int(std::lround(-grid.vertices[v].y() / pixel_size));
    if (x < 0 || y < 0 || x >= d.regions.cols || y >= d.regions.rows) continue;
    const int reg = d.regions.at<int>(y, x);
    if (reg < 0 || r.in_margin[size_t(v)] || reg == paper_region) continue;  // the free surface of the object
    pairs.push_back({double(d.region_height[size_t(reg)]), r.height[size_t(v)]});
    num += pairs.back().first * pairs.back().second, den += pairs.back().first * pairs.back().first;
  }
  f.samples = long(pairs.size());
  if (pairs.empty()) return f;
  f.scale = den > 0 ? num / den : 0;
  double s2 = 0;
  for (const auto& [lv, h] : pairs) s2 += (h - f.scale * lv) * (h - f.scale * lv);
  f.rms_steps = std::sqrt(s2 / double(pairs.size())) / (f.scale > 0 ? f.scale : 1);
  return f;
}

}  // namespace rktest
