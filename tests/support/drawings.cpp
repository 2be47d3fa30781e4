#include "drawings.h"

#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>
#include <opencv2/imgcodecs.hpp>

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

namespace {
double to_segment(const reliefkit::Vec2& p, const reliefkit::Vec2& a, const reliefkit::Vec2& b) {
  const reliefkit::Vec2 d = b - a;
  const double t = std::clamp((p - a).dot(d) / d.squaredNorm(), 0.0, 1.0);
  return (a + t * d - p).norm();
}
double to_rect(const reliefkit::Vec2& p, double x0, double y0, double x1, double y1) {
  using reliefkit::Vec2;
  return std::min({to_segment(p, Vec2(x0, y0), Vec2(x1, y0)), to_segment(p, Vec2(x1, y0), Vec2(x1, y1)),
                   to_segment(p, Vec2(x1, y1), Vec2(x0, y1)), to_segment(p, Vec2(x0, y1), Vec2(x0, y0))});
}
}  // namespace

double nested_truth_distance(const reliefkit::Vec2& p, double s) {
  using reliefkit::Vec2;
  const double d = std::min({to_rect(p, 40 * s, 40 * s, 560 * s, 560 * s), std::abs((p - Vec2(160, 160) * s).norm() - 70 * s),
                             std::abs((p - Vec2(420, 170) * s).norm() - 90 * s), std::abs((p - Vec2(420, 170) * s).norm() - 40 * s),
                             to_rect(p, 120 * s, 340 * s, 460 * s, 480 * s), to_segment(p, Vec2(290, 340) * s, Vec2(290, 480) * s)});
  return d;
}

std::vector<reliefkit::Vec2> nested_truth_samples(double s) {
  using reliefkit::Vec2;
  std::vector<Vec2> out;
  auto seg = [&](Vec2 a, Vec2 b) {
    const int n = int((b - a).norm()) + 1;
    for (int k = 0; k < n; ++k) out.push_back(a + (b - a) * (double(k) / n));
  };
  auto rect = [&](double x0, double y0, double x1, double y1) {
    seg(Vec2(x0, y0), Vec2(x1, y0)), seg(Vec2(x1, y0), Vec2(x1, y1)), seg(Vec2(x1, y1), Vec2(x0, y1)), seg(Vec2(x0, y1), Vec2(x0, y0));
  };
  auto circle = [&](Vec2 c, double r) {
    const int n = int(2 * 3.14159265358979 * r) + 1;
    for (int k = 0; k < n; ++k) out.push_back(c + r * Vec2(std::cos(2 * 3.14159265358979 * k / n), std::sin(2 * 3.14159265358979 * k / n)));
  };
  rect(40 * s, 40 * s, 560 * s, 560 * s);
  circle(Vec2(160, 160) * s, 70 * s), circle(Vec2(420, 170) * s, 90 * s), circle(Vec2(420, 170) * s, 40 * s);
  rect(120 * s, 340 * s, 460 * s, 480 * s);
  seg(Vec2(290, 340) * s, Vec2(290, 480) * s);
  return out;
}

int nested_true_level(const reliefkit::Vec2& p, bool right_half_higher, double s, double clearance) {
  using reliefkit::Vec2;
  if (nested_truth_distance(p, s) < clearance) return -1;
  const Vec2 q = p / s;  // in the drawing at scale 1
  if (q.x() < 40 || q.x() > 560 || q.y() < 40 || q.y() > 560) return -1;  // the paper
  if ((q - Vec2(160, 160)).norm() < 70) return 2;
  const double ring = (q - Vec2(420, 170)).norm();
  if (ring < 40) return 3;
  if (ring < 90) return 2;
  if (q.x() > 120 && q.x() < 460 && q.y() > 340 && q.y() < 480) return (q.x() > 290) == right_half_higher ? 3 : 2;
  return 1;
}

void add_shading(cv::Mat& img, cv::Rect area, double stroke, double spacing) {
  // Hatching on the left half, stippling on the right half.
  const int mid = area.x + area.width / 2;
  for (double y = area.y; y < area.y + area.height; y += 2 * spacing)
    for (double x = area.x; x < mid - stroke; x += spacing * 1.5)
      cv::line(img, cv::Point(int(x), int(y)), cv::Point(int(x + stroke * 0.7), int(y + stroke * 0.7)), cv::Scalar(0), 1,
               cv::LINE_AA);
  for (double y = area.y; y < area.y + area.height; y += spacing)
    for (double x = mid + ((int(y) / int(spacing)) % 2) * spacing / 2; x < area.x + area.width; x += spacing)
      cv::circle(img, cv::Point(int(x), int(y)), 1, cv::Scalar(0), -1, cv::LINE_AA);
}

namespace {
// Inside `poly`, at least `clearance` px from its edge (negative: up to -clearance px outside it).
cv::Mat interior(cv::Size size, const std::vector<cv::Point>& poly, double clearance) {
  cv::Mat m(size, CV_8U, cv::Scalar(0));
  cv::fillPoly(m, std::vector<std::vector<cv::Point>>{poly}, cv::Scalar(255));
  const int d = 2 * int(std::ceil(std::abs(clearance))) + 1;
  const cv::Mat disc = cv::getStructuringElement(cv::MORPH_ELLIPSE, cv::Size(d, d));
  if (clearance >= 0) cv::erode(m, m, disc); else cv::dilate(m, m, disc);
  return m;
}
}  // namespace

ShadedTool shaded_tool_drawing(int outline_px, double clearance) {
  cv::Mat img(900, 700, CV_8UC1, cv::Scalar(255));
  std::vector<cv::Point> tool, scar;
  for (int k = 0; k < 240; ++k) {
    const double t = 2 * M_PI * k / 240;
    tool.emplace_back(int(350 + 250 * std::cos(t) + 20 * std::cos(3 * t)), int(450 + 360 * std::sin(t) + 15 * std::sin(2 * t)));
    scar.emplace_back(int(360 + 120 * std::cos(t)), int(560 + 150 * std::sin(t) + 10 * std::sin(3 * t)));
  }
  for (int k = 0; k < 14; ++k)  // ripple hatching: short curved strokes with free ends
    cv::ellipse(img, {340, 170 + 9 * k}, {70, 30}, 0, 200, 340, cv::Scalar(40), 1, cv::LINE_AA);
  cv::RNG rng(3);
  for (int k = 0; k < 300; ++k)  // stippling inside the scar
    cv::circle(img, {rng.uniform(300, 420), rng.uniform(500, 620)}, 1, cv::Scalar(20), -1, cv::LINE_AA);
  cv::polylines(img, std::vector<std::vector<cv::Point>>{scar}, true, cv::Scalar(0), 2, cv::LINE_AA);
  cv::Mat across(img.size(), CV_8U, cv::Scalar(0)), inside(img.size(), CV_8U, cv::Scalar(0));
  cv::line(across, {60, 300}, {640, 330}, cv::Scalar(255), 3, cv::LINE_AA);  // a line across the tool, ending on its outline
  cv::fillPoly(inside, std::vector<std::vector<cv::Point>>{tool}, cv::Scalar(255));
  img.setTo(0, across & inside);
  cv::polylines(img, std::vector<std::vector<cv::Point>>{tool}, true, cv::Scalar(0), outline_px, cv::LINE_AA);
  ShadedTool out;
  out.tool = interior(img.size(), tool, clearance + 0.5 * outline_px) & ~interior(img.size(), scar, -clearance);
  out.scar = interior(img.size(), scar, clearance);
  cv::Mat paper = img * 0.9 + 14;  // off-white
  out.image = paper_and_jpeg(paper, 0.02, 75);
  return out;
}

ShadedTool scarred_flake_drawing(double clearance) {
  cv::Mat img(900, 700, CV_8UC1, cv::Scalar(255));
  std::vector<cv::Point> outline;
  for (int k = 0; k < 200; ++k) {
    const double t = 2 * M_PI * k / 200;
    outline.emplace_back(int(350 + 250 * std::cos(t) + 20 * std::cos(3 * t)), int(450 + 360 * std::sin(t) + 15 * std::sin(2 * t)));
  }
  cv::line(img, {150, 250}, {560, 330}, cv::Scalar(0), 3, cv::LINE_AA);
  cv::line(img, {130, 560}, {580, 620}, cv::Scalar(0), 3, cv::LINE_AA);
  cv::line(img, {350, 290}, {360, 590}, cv::Scalar(0), 3, cv::LINE_AA);
  for (int k = 0; k < 14; ++k) cv::ellipse(img, {340, 150 + 8 * k}, {60, 30}, 0, 200, 340, cv::Scalar(60), 1, cv::LINE_AA);
  cv::RNG rng(3);
  for (int k = 0; k < 400; ++k) cv::circle(img, {rng.uniform(400, 540), rng.uniform(660, 760)}, 1, cv::Scalar(30), -1, cv::LINE_AA);
  cv::polylines(img, std::vector<std::vector<cv::Point>>{outline}, true, cv::Scalar(0), 8, cv::LINE_AA);
  ShadedTool out;
  out.tool = interior(img.size(), outline, clearance + 4);
  out.scar = cv::Mat(img.size(), CV_8U, cv::Scalar(0));
  cv::Mat paper = img * 0.92 + 12;
  out.image = paper_and_jpeg(paper, 0.02, 75);
  return out;
}

namespace {
// Parallel strokes `spacing` px apart at `angle` (radians) across the whole image, kept where `mask` is set.
void hatch(cv::Mat& img, const cv::Mat& mask, double angle, double spacing) {
  cv::Mat strokes(img.size(), CV_8U, cv::Scalar(0));
  const double c = std::cos(angle), s = std::sin(angle), reach = img.cols + img.rows;
  for (double o = -reach; o <= reach; o += spacing) {
    const cv::Point2d mid(img.cols / 2.0 - s * o, img.rows / 2.0 + c * o);
    cv::line(strokes, cv::Point(mid.x - c * reach, mid.y - s * reach), cv::Point(mid.x + c * reach, mid.y + s * reach),
             cv::Scalar(255), 1, cv::LINE_AA);
  }
  cv::Mat keep;
  cv::min(strokes, mask, keep);
  cv::Mat inked = 255 - keep;
  cv::min(img, inked, img);
}
}  // namespace

HatchedSections hatched_sections_drawing(double clearance) {
  cv::Mat img(620, 760, CV_8UC1, cv::Scalar(255));
  std::vector<cv::Point> lens, rect{{420, 90}, {700, 90}, {700, 530}, {420, 530}};
  for (int k = 0; k < 200; ++k) {
    const double t = 2 * M_PI * k / 200;
    lens.emplace_back(int(200 + 120 * std::cos(t)), int(310 + 230 * std::sin(t) * (0.8 + 0.2 * std::cos(t))));
  }
  const cv::Point disc_centre(560, 310);
  const int disc_radius = 70;
  cv::Mat lens_in(img.size(), CV_8U, cv::Scalar(0)), rect_in = lens_in.clone();
  cv::fillPoly(lens_in, std::vector<std::vector<cv::Point>>{lens}, cv::Scalar(255));
  cv::fillPoly(rect_in, std::vector<std::vector<cv::Point>>{rect}, cv::Scalar(255));
  cv::circle(rect_in, disc_centre, disc_radius, cv::Scalar(0), -1);
  hatch(img, lens_in, 0.8, 9);
  hatch(img, rect_in, 0.6, 12);
  hatch(img, rect_in, 0.6 + M_PI / 2, 12);
  cv::polylines(img, std::vector<std::vector<cv::Point>>{lens, rect}, true, cv::Scalar(0), 3, cv::LINE_AA);
  cv::circle(img, disc_centre, disc_radius, cv::Scalar(0), 3, cv::LINE_AA);
  HatchedSections out;
  out.lens = interior(img.size(), lens, clearance + 1.5);
  out.rect = interior(img.size(), rect, clearance + 1.5);
  std::vector<cv::Point> disc;
  cv::ellipse2Poly(disc_centre, {disc_radius, disc_radius}, 0, 0, 360, 3, disc);
  out.disc = interior(img.size(), disc, clearance + 1.5);
  out.rect &= ~interior(img.size(), disc, -clearance - 1.5);
  out.image = paper_and_jpeg(img, 0.02, 75);
  return out;
}

cv::Mat paper_and_jpeg(const cv::Mat& grey8, double sigma, int quality) {
  cv::Mat f;
  grey8.convertTo(f, CV_32F, 1.0 / 255);
  cv::Mat noise(f.size(), CV_32F);
  cv::RNG rng(7);
  rng.fill(noise, cv::RNG::NORMAL, 0, sigma);
  f += noise;
  cv::Mat n8;
  f.convertTo(n8, CV_8U, 255);
  std::vector<uchar> jpeg;
  cv::imencode(".jpg", n8, jpeg, {cv::IMWRITE_JPEG_QUALITY, quality});
  return cv::imdecode(jpeg, cv::IMREAD_GRAYSCALE);
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

TrueLevelError true_level_error(const std::vector<reliefkit::Vec2>& pixel, const reliefkit::DrawingRelief& r,
                                double step_height, double scale) {
  TrueLevelError best;
  best.rms = 1e300;
  for (bool right_higher : {false, true}) {
    TrueLevelError e;
    e.right_half_higher = right_higher;
    double s2 = 0;
    for (size_t v = 0; v < pixel.size(); ++v) {
      if (r.in_margin[v] || !std::isfinite(pixel[v].x())) continue;
      const int level = nested_true_level(pixel[v], right_higher, scale);
      if (level < 1) continue;
      const double err = r.height[v] / step_height - level;
      s2 += err * err, e.worst = std::max(e.worst, std::abs(err)), ++e.samples;
    }
    e.rms = e.samples ? std::sqrt(s2 / double(e.samples)) : 1e300;
    if (e.rms < best.rms) best = e;
  }
  return best;
}

}  // namespace rktest
