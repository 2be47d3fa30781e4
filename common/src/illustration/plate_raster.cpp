// ReliefKit — the plate's frame and depth raster. See plate_raster.h.
#include "plate_raster.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <opencv2/imgproc.hpp>

namespace reliefkit {
namespace {

constexpr double kMostPixels = 60e6;  // about A3 at 600 dpi
constexpr double kSmallHoleEdges = 3;  // the scan's holes filled in the drawing: at most this many mean edges across

// Per-vertex area-weighted normals (for the Lambertian shading).
std::vector<Vec3> vertex_normals(const TriMesh& mesh) {
  std::vector<Vec3> n(mesh.vertices.size(), Vec3::Zero());
  for (const auto& f : mesh.faces) {
    const Vec3 fn = (mesh.vertices[size_t(f[1])] - mesh.vertices[size_t(f[0])]).cross(mesh.vertices[size_t(f[2])] - mesh.vertices[size_t(f[0])]);
    for (int v : f) n[size_t(v)] += fn;
  }
  for (auto& v : n) v = v.norm() > 0 ? Vec3(v.normalized()) : Vec3::Zero();
  return n;
}

// Grey per vertex from a light over the viewer's left shoulder (the illustrator's convention:
// light from the top left), two-sided so that a surface seen from behind is not black.
std::vector<double> lambertian(const TriMesh& mesh, const PageFrame& frame) {
  const Vec3 light = (-frame.ahead + 0.5 * frame.up - 0.5 * frame.right).normalized();
  const std::vector<Vec3> n = vertex_normals(mesh);
  std::vector<double> g(n.size());
  for (size_t i = 0; i < n.size(); ++i) g[i] = 0.25 + 0.75 * std::abs(n[i].dot(light));
  return g;
}

struct ScreenVertex {
  double x, y, z, grey;
};

// One triangle into the raster: nearest depth wins, its grey with it, and whether it was seen
// from behind (its outward side turned away from the viewer).
void draw_triangle(const ScreenVertex (&t)[3], bool from_behind, cv::Mat& depth, cv::Mat& grey, cv::Mat& behind) {
  const double area = (t[1].x - t[0].x) * (t[2].y - t[0].y) - (t[2].x - t[0].x) * (t[1].y - t[0].y);
  if (std::abs(area) < 1e-12) return;
  const int x0 = std::max(0, int(std::floor(std::min({t[0].x, t[1].x, t[2].x})))),
            x1 = std::min(depth.cols - 1, int(std::ceil(std::max({t[0].x, t[1].x, t[2].x})))),
            y0 = std::max(0, int(std::floor(std::min({t[0].y, t[1].y, t[2].y})))),
            y1 = std::min(depth.rows - 1, int(std::ceil(std::max({t[0].y, t[1].y, t[2].y}))));
  for (int y = y0; y <= y1; ++y)
    for (int x = x0; x <= x1; ++x) {
      const double px = x + 0.5, py = y + 0.5;
      double w[3];
      for (int k = 0; k < 3; ++k) {
        const ScreenVertex &a = t[(k + 1) % 3], &b = t[(k + 2) % 3];
        w[k] = ((b.x - a.x) * (py - a.y) - (px - a.x) * (b.y - a.y)) / area;
      }
      if (w[0] < -1e-9 || w[1] < -1e-9 || w[2] < -1e-9) continue;
      const double z = w[0] * t[0].z + w[1] * t[1].z + w[2] * t[2].z;
      double& d = depth.at<double>(y, x);
      if (z >= d) continue;
      d = z;
      const double g = w[0] * t[0].grey + w[1] * t[1].grey + w[2] * t[2].grey;
      grey.at<uchar>(y, x) = cv::saturate_cast<uchar>(255 * std::clamp(g, 0.0, 1.0));
      behind.at<uchar>(y, x) = from_behind ? 255 : 0;
    }
}

// The holes of the drawing: pixels where the paper or the back of the surface shows.
cv::Mat hole_pixels(const cv::Mat& depth, const cv::Mat& behind) {
  cv::Mat paper;
  cv::compare(depth, std::numeric_limits<double>::infinity(), paper, cv::CMP_EQ);
  return paper | behind;
}

// The holes to fill: connected hole pixels inside the drawing (off the raster's border) at most
// `most_px` across — the scan's small holes, not the paper round the object or between its parts
// (nor a hole a drawing of this size shows: a broken vessel's, a pierced seal's).
std::vector<cv::Point> small_holes(const cv::Mat& holes, double most_px) {
  cv::Mat labels, stats, centroids;
  const int count = cv::connectedComponentsWithStats(holes, labels, stats, centroids, 8, CV_32S);
  std::vector<char> small(size_t(count), 0);
  for (int k = 1; k < count; ++k) {
    const int x = stats.at<int>(k, cv::CC_STAT_LEFT), y = stats.at<int>(k, cv::CC_STAT_TOP);
    const int w = stats.at<int>(k, cv::CC_STAT_WIDTH), h = stats.at<int>(k, cv::CC_STAT_HEIGHT);
    const bool inside = x > 0 && y > 0 && x + w < holes.cols && y + h < holes.rows;
    small[size_t(k)] = inside && std::max(w, h) <= most_px;
  }
  std::vector<cv::Point> pixels;
  for (int y = 0; y < holes.rows; ++y)
    for (int x = 0; x < holes.cols; ++x)
      if (small[size_t(labels.at<int>(y, x))]) pixels.emplace_back(x, y);
  return pixels;
}

// The scan's small holes (a few triangles across, left by the scanner or by decimation) would
// show as dots of paper or of the surface's dark back: filled from their rim inwards, each pixel
// the mean grey and depth of its filled or surface neighbours.
void fill_small_holes(DepthRaster& r, const cv::Mat& behind, double most_px) {
  const cv::Mat holes = hole_pixels(r.depth, behind);
  std::vector<cv::Point> left = small_holes(holes, most_px);
  cv::Mat known = holes == 0;
  while (!left.empty()) {
    std::vector<cv::Point> next, done;
    std::vector<std::pair<double, double>> values;  // grey, depth
    for (const cv::Point& p : left) {
      double grey = 0, depth = 0;
      int n = 0;
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          const cv::Point q(p.x + dx, p.y + dy);
          if (q.x < 0 || q.y < 0 || q.x >= known.cols || q.y >= known.rows || !known.at<uchar>(q)) continue;
          grey += r.grey.at<uchar>(q), depth += r.depth.at<double>(q), ++n;
        }
      if (n == 0) next.push_back(p);
      else done.push_back(p), values.emplace_back(grey / n, depth / n);
    }
    if (done.empty()) break;
    for (size_t k = 0; k < done.size(); ++k) {
      r.grey.at<uchar>(done[k]) = cv::saturate_cast<uchar>(values[k].first);
      r.depth.at<double>(done[k]) = values[k].second, known.at<uchar>(done[k]) = 255;
    }
    left.swap(next);
  }
}

// The mean edge length of the mesh, in mesh units.
double mean_edge_length(const TriMesh& mesh) {
  double sum = 0;
  for (const auto& f : mesh.faces)
    for (int k = 0; k < 3; ++k) sum += (mesh.vertices[size_t(f[k])] - mesh.vertices[size_t(f[(k + 1) % 3])]).norm();
  return mesh.faces.empty() ? 0 : sum / (3.0 * double(mesh.faces.size()));
}
}  // namespace

PageFrame page_frame(const TriMesh& mesh, const PlateView& view, double mm_per_unit) {
  PageFrame f;
  if (!view.direction.allFinite() || view.direction.norm() < 1e-12) throw InputError("The view direction must not be zero.");
  f.ahead = view.direction.normalized();
  Vec3 up = view.up - view.up.dot(f.ahead) * f.ahead;
  if (up.norm() < 1e-9) up = f.ahead.unitOrthogonal();  // up along the view: any perpendicular
  f.up = up.normalized();
  f.right = f.ahead.cross(f.up);
  double lo_x = 1e300, hi_x = -1e300, lo_y = 1e300, hi_y = -1e300;
  f.nearest = 1e300, f.farthest = -1e300;
  for (const auto& p : mesh.vertices) {
    lo_x = std::min(lo_x, p.dot(f.right)), hi_x = std::max(hi_x, p.dot(f.right));
    lo_y = std::min(lo_y, p.dot(f.up)), hi_y = std::max(hi_y, p.dot(f.up));
    f.nearest = std::min(f.nearest, p.dot(f.ahead)), f.farthest = std::max(f.farthest, p.dot(f.ahead));
  }
  f.left = lo_x;
  f.top = hi_y;
  f.mm_per_unit = mm_per_unit;
  f.drawing_mm = Vec2((hi_x - lo_x) * f.mm_per_unit, (hi_y - lo_y) * f.mm_per_unit);
  if (!(f.drawing_mm.x() > 1e-3 && f.drawing_mm.y() > 1e-3))
    throw InputError("Seen from this view the mesh has no area (it is seen edge-on, or it is a line or a point): choose "
                     "another view direction.");
  return f;
}

DepthRaster rasterize(const TriMesh& mesh, const std::vector<double>& grey, const PageFrame& frame, const PlateParams& params) {
  DepthRaster r;
  r.px_per_mm = params.dpi / 25.4;
  const double w = std::ceil(frame.drawing_mm.x() * r.px_per_mm), h = std::ceil(frame.drawing_mm.y() * r.px_per_mm);
  if (w * h > kMostPixels) throw InputError("The shading would be over 60 million pixels at this size: lower its dpi or the scale.");
  r.depth = cv::Mat(int(std::max(1.0, h)), int(std::max(1.0, w)), CV_64F, cv::Scalar(std::numeric_limits<double>::infinity()));
  r.grey = cv::Mat(r.depth.size(), CV_8U, cv::Scalar(255));
  r.hidden_depth = params.hidden_px / r.px_per_mm / frame.mm_per_unit;
  const std::vector<double> g = grey.empty() ? lambertian(mesh, frame) : grey;
  cv::Mat behind(r.depth.size(), CV_8U, cv::Scalar(0));
  for (const auto& f : mesh.faces) {
    ScreenVertex t[3];
    for (int k = 0; k < 3; ++k) {
      const Vec3& p = mesh.vertices[size_t(f[k])];
      const Vec2 mm = frame.to_mm(p);
      t[k] = {mm.x() * r.px_per_mm, mm.y() * r.px_per_mm, frame.depth(p), g[size_t(f[k])]};
    }
    const Vec3 outward = (mesh.vertices[size_t(f[1])] - mesh.vertices[size_t(f[0])]).cross(mesh.vertices[size_t(f[2])] - mesh.vertices[size_t(f[0])]);
    draw_triangle(t, outward.dot(frame.ahead) > 0, r.depth, r.grey, behind);
  }
  fill_small_holes(r, behind, std::max(2.0, kSmallHoleEdges * mean_edge_length(mesh) * frame.mm_per_unit * r.px_per_mm));
  return r;
}

std::vector<std::vector<Vec2>> silhouette_outline(const DepthRaster& raster, double simplify_px) {
  cv::Mat seen(raster.depth.size(), CV_8U, cv::Scalar(0));
  for (int y = 0; y < seen.rows; ++y)
    for (int x = 0; x < seen.cols; ++x) seen.at<uchar>(y, x) = std::isfinite(raster.depth.at<double>(y, x)) ? 255 : 0;
  std::vector<std::vector<cv::Point>> contours;
  cv::findContours(seen, contours, cv::RETR_LIST, cv::CHAIN_APPROX_NONE);
  std::vector<std::vector<Vec2>> outline;
  for (const auto& contour : contours) {
    if (contour.size() < 16) continue;
    std::vector<cv::Point> simple;
    cv::approxPolyDP(contour, simple, std::max(simplify_px, 0.25), true);
    std::vector<Vec2> line;
    for (const cv::Point& q : simple) line.emplace_back((q.x + 0.5) / raster.px_per_mm, (q.y + 0.5) / raster.px_per_mm);
    line.push_back(line.front());
    outline.push_back(std::move(line));
  }
  return outline;
}

}  // namespace reliefkit
