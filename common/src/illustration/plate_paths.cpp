// ReliefKit — the plate's visible curves: chained, cut where they pass behind the surface,
// simplified. See plate_raster.h.
#include <algorithm>
#include <cmath>

#include "plate_raster.h"

namespace reliefkit {
namespace {

// The segments chained into polylines of point indices: from each point of degree other than 2,
// then the closed loops (their first point repeated at the end).
std::vector<std::vector<int>> chain_segments(int n_points, const std::vector<std::array<int, 2>>& segments) {
  std::vector<std::vector<int>> next(static_cast<size_t>(n_points));
  for (size_t s = 0; s < segments.size(); ++s)
    for (int k = 0; k < 2; ++k) next[size_t(segments[s][k])].push_back(int(s));
  std::vector<char> used(segments.size(), 0);
  std::vector<std::vector<int>> chains;
  auto walk = [&](int start) {
    for (int s : next[size_t(start)]) {
      if (used[size_t(s)]) continue;
      std::vector<int> chain{start};
      int at = start, seg = s;
      while (seg >= 0) {
        used[size_t(seg)] = 1;
        at = segments[size_t(seg)][0] == at ? segments[size_t(seg)][1] : segments[size_t(seg)][0];
        chain.push_back(at);
        seg = -1;
        if (next[size_t(at)].size() == 2)
          for (int t : next[size_t(at)])
            if (!used[size_t(t)]) seg = t;
      }
      chains.push_back(std::move(chain));
    }
  };
  for (int p = 0; p < n_points; ++p)
    if (next[size_t(p)].size() != 2) walk(p);
  for (int p = 0; p < n_points; ++p) walk(p);  // what is left: closed loops
  return chains;
}

// A point is visible when it is no farther than the nearest surface around its pixel (3 x 3, so
// that a curve on a steep slope is not cut by its own surface) plus the tolerance.
bool visible(const Vec3& p, const PageFrame& frame, const DepthRaster& r) {
  const Vec2 px = frame.to_mm(p) * r.px_per_mm;
  const int cx = int(std::floor(px.x())), cy = int(std::floor(px.y()));
  double nearest_far = -1e300;
  for (int y = cy - 1; y <= cy + 1; ++y)
    for (int x = cx - 1; x <= cx + 1; ++x) {
      if (x < 0 || y < 0 || x >= r.depth.cols || y >= r.depth.rows) return true;  // at the drawing's edge
      nearest_far = std::max(nearest_far, r.depth.at<double>(y, x));
    }
  return frame.depth(p) <= nearest_far + r.hidden_depth;
}

// Douglas–Peucker within `tol` (millimetres).
void simplify(const std::vector<Vec2>& in, size_t a, size_t b, double tol, std::vector<char>& keep) {
  if (b <= a + 1) return;
  const Vec2 d = in[b] - in[a];
  const double len = d.norm();
  double worst = -1;
  size_t at = a;
  for (size_t k = a + 1; k < b; ++k) {
    const Vec2 v = in[k] - in[a];
    const double dist = len > 0 ? std::abs(d.x() * v.y() - d.y() * v.x()) / len : v.norm();
    if (dist > worst) worst = dist, at = k;
  }
  if (worst <= tol) return;
  keep[at] = 1;
  simplify(in, a, at, tol, keep);
  simplify(in, at, b, tol, keep);
}

void emit(Plate& plate, std::vector<Vec2>& run, const PlateCurves& layer, double tol_mm) {
  if (run.size() >= 2) {
    std::vector<char> keep(run.size(), 0);
    keep.front() = keep.back() = 1;
    simplify(run, 0, run.size() - 1, tol_mm, keep);
    PlatePath path{{}, layer.width_mm, layer.name};
    for (size_t k = 0; k < run.size(); ++k)
      if (keep[k]) path.points.push_back(run[k]);
    plate.paths.push_back(std::move(path));
  }
  run.clear();
}
}  // namespace

void add_visible_paths(Plate& plate, const PlateCurves& layer, const PageFrame& frame, const DepthRaster& r,
                       const PlateParams& params) {
  const double step_px = 0.5, tol_mm = params.simplify_px / r.px_per_mm;
  for (const auto& chain : chain_segments(int(layer.points.size()), layer.segments)) {
    std::vector<Vec2> run;
    for (size_t k = 0; k + 1 < chain.size(); ++k) {
      const Vec3 &a = layer.points[size_t(chain[k])], &b = layer.points[size_t(chain[k + 1])];
      const double len_px = (frame.to_mm(b) - frame.to_mm(a)).norm() * r.px_per_mm;
      const int n = std::max(1, int(std::ceil(len_px / step_px)));
      (visible(0.5 * (a + b), frame, r) ? plate.visible_segments : plate.hidden_segments) += 1;
      for (int s = k == 0 ? 0 : 1; s <= n; ++s) {
        const Vec3 q = a + (b - a) * (double(s) / n);
        if (visible(q, frame, r)) run.push_back(frame.to_mm(q));
        else emit(plate, run, layer, tol_mm);
      }
    }
    emit(plate, run, layer, tol_mm);
  }
}

}  // namespace reliefkit
