// ReliefKit — the drawing's curves and region levels placed on its relief (thesis sect. 7.4), for
// the layers a filter shows beside the relief. See drawing_relief.h.
#include <algorithm>
#include <cmath>
#include <unordered_map>

#include "reliefkit/drawing/drawing_relief.h"

namespace reliefkit {

Polylines drawing_polylines(const DrawingCurves& dc, double pixel_size) {
  Polylines pl;
  for (size_t k = 0; k < dc.curves.size(); ++k) {
    const int first = int(pl.points.size());
    for (const auto& q : dc.curves[k]) {
      pl.points.push_back(Vec3(q.x() * pixel_size, -q.y() * pixel_size, 0));
      pl.strength.push_back(double(k));
    }
    for (int i = first; i + 1 < int(pl.points.size()); ++i) pl.segments.push_back({i, i + 1});
  }
  return pl;
}

std::vector<double> region_levels(const DrawingInterpretation& di, const std::vector<Vec2>& pixel) {
  std::vector<double> level(pixel.size(), -1);
  for (size_t v = 0; v < pixel.size(); ++v) {
    if (!pixel[v].allFinite()) continue;
    const long x = std::lround(pixel[v].x()), y = std::lround(pixel[v].y());
    const int reg = (x >= 0 && y >= 0 && x < di.regions.cols && y < di.regions.rows) ? di.regions.at<int>(int(y), int(x)) : -1;
    if (reg >= 0) level[v] = double(di.region_height[size_t(reg)]);
  }
  return level;
}

namespace {
// The covered vertices by their pixel positions, in square cells.
class PixelHash {
 public:
  PixelHash(const std::vector<Vec2>& pixel, double cell) : pixel_(pixel), cell_(cell) {
    for (int v = 0; v < int(pixel.size()); ++v)
      if (std::isfinite(pixel[size_t(v)].x())) bins_[key(pixel[size_t(v)].x(), pixel[size_t(v)].y())].push_back(v);
  }
  // The vertex nearest to q among the 3 x 3 cells around it; -1 when they are empty.
  int nearest(const Vec2& q) const {
    int best = -1;
    double bd = 1e300;
    for (int ox = -1; ox <= 1; ++ox)
      for (int oy = -1; oy <= 1; ++oy) {
        const auto it = bins_.find(key(q.x() + ox * cell_, q.y() + oy * cell_));
        if (it == bins_.end()) continue;
        for (int v : it->second) {
          const double dd = (pixel_[size_t(v)] - q).squaredNorm();
          if (dd < bd) bd = dd, best = v;
        }
      }
    return best;
  }

 private:
  long long key(double x, double y) const {
    return (long long)std::floor(x / cell_) * 1000003LL + (long long)std::floor(y / cell_);
  }
  const std::vector<Vec2>& pixel_;
  double cell_;
  std::unordered_map<long long, std::vector<int>> bins_;
};
}  // namespace

Polylines curves_on_projected_relief(const DrawingCurves& dc, const DrawingProjection& proj, const TriMesh& relief) {
  Polylines pl = drawing_polylines(dc, proj.pixel_size);
  const PixelHash hash(proj.pixel, std::max(1.0, 2 * proj.edge_px));
  std::vector<char> keep(pl.points.size(), 1);
  size_t i = 0;
  for (const auto& c : dc.curves)
    for (const auto& q : c) {
      const int best = hash.nearest(q);
      if (best < 0) {
        keep[i] = 0;
        pl.points[i++] = Vec3::Zero();
        continue;
      }
      const Vec2 off = q - proj.pixel[size_t(best)];
      pl.points[i++] = relief.vertices[size_t(best)] + proj.pixel_size * (off.x() * proj.right - off.y() * proj.up);
    }
  std::vector<std::array<int, 2>> kept;
  for (const auto& s : pl.segments)
    if (keep[size_t(s[0])] && keep[size_t(s[1])]) kept.push_back(s);
  pl.segments = kept;
  return pl;
}

Polylines curves_on_grid_relief(const DrawingCurves& dc, double pixel_size, const cv::Rect& area, double cell,
                                const std::vector<double>& height, DrawingBase base, double circumference, double front) {
  Polylines pl = drawing_polylines(dc, pixel_size);
  // The grid's size, as drawing_grid makes it.
  const int nx = std::max(2, int(std::ceil((area.width - 1) / cell)) + 1);
  const int ny = std::max(2, int(std::ceil((area.height - 1) / cell)) + 1);
  if (height.size() != size_t(nx) * ny) throw InputError("curves_on_grid_relief: one height per grid vertex is needed.");
  auto H = [&](int a, int b) { return height[size_t(b * nx + a)]; };
  std::vector<double> hgt(pl.points.size(), 0);
  for (size_t i = 0; i < pl.points.size(); ++i) {
    const double gx = std::clamp((pl.points[i].x() / pixel_size - area.x) / cell, 0.0, nx - 1.0);
    const double gy = std::clamp((-pl.points[i].y() / pixel_size - area.y) / cell, 0.0, ny - 1.0);
    const int i0 = std::min(nx - 2, int(gx)), j0 = std::min(ny - 2, int(gy));
    const double fx = gx - i0, fy = gy - j0;
    hgt[i] = (1 - fy) * ((1 - fx) * H(i0, j0) + fx * H(i0 + 1, j0)) + fy * ((1 - fx) * H(i0, j0 + 1) + fx * H(i0 + 1, j0 + 1));
  }
  TriMesh points;
  points.vertices = pl.points;
  pl.points = relief_surface(points, hgt, base, circumference, front).vertices;
  return pl;
}

}  // namespace reliefkit
