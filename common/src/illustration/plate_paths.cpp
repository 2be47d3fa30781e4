// ReliefKit — the plate's visible curves: chained, cut where they pass behind the surface,
// simplified. See plate_raster.h.
#include <algorithm>
#include <cmath>

#include "plate_raster.h"
#include "reliefkit/base/zero_crossings.h"

namespace reliefkit {
namespace {

// On the mesh's drawing (within a pixel of the raster): curves off it belong to another mesh.
bool on_drawing(const Vec3& p, const PageFrame& frame, const DepthRaster& r) {
  const Vec2 px = frame.to_mm(p) * r.px_per_mm;
  return px.x() >= -1 && px.y() >= -1 && px.x() <= r.depth.cols + 1 && px.y() <= r.depth.rows + 1;
}

// A point is visible when it is no farther than the nearest surface around its pixel (3 x 3, so
// that a curve on a steep slope is not cut by its own surface) plus the tolerance.
bool visible(const Vec3& p, const PageFrame& frame, const DepthRaster& r) {
  if (!on_drawing(p, frame, r)) return false;
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

// The technical pens' weights relative to the middle one: 0.5, 0.35 and 0.25 mm.
constexpr double kHeavy = 0.5 / 0.35, kLight = 0.25 / 0.35;

double chain_length(const std::vector<int>& chain, const PlateCurves& layer) {
  double length = 0;
  for (size_t k = 0; k + 1 < chain.size(); ++k)
    length += (layer.points[size_t(chain[k + 1])] - layer.points[size_t(chain[k])]).norm();
  return length;
}

// Each chain's width by its strength (the mean of its points'): the strongest third of the
// layer's curve length heavy, the weakest third light; one width when the strengths do not vary.
std::vector<double> widths_by_strength(const std::vector<std::vector<int>>& chains, const PlateCurves& layer) {
  std::vector<double> width(chains.size(), layer.width_mm), strength(chains.size(), 0), length(chains.size());
  if (layer.strength.size() != layer.points.size()) return width;
  for (size_t c = 0; c < chains.size(); ++c) {
    for (int k : chains[c]) strength[c] += std::abs(layer.strength[size_t(k)]) / double(chains[c].size());
    length[c] = chain_length(chains[c], layer);
  }
  const auto [lo, hi] = std::minmax_element(strength.begin(), strength.end());
  if (chains.empty() || !(*hi - *lo > 1e-9 * std::max(1.0, *hi))) return width;
  std::vector<size_t> order(chains.size());
  for (size_t c = 0; c < order.size(); ++c) order[c] = c;
  std::sort(order.begin(), order.end(), [&](size_t a, size_t b) { return strength[a] < strength[b]; });
  double total = 0, below = 0;
  for (double l : length) total += l;
  for (size_t c : order) {
    const double middle = (below + 0.5 * length[c]) / std::max(total, 1e-300);  // of the chain, in the cumulative length
    width[c] = layer.width_mm * (middle < 1 / 3.0 ? kLight : middle > 2 / 3.0 ? kHeavy : 1.0);
    below += length[c];
  }
  return width;
}

std::vector<double> chain_widths(const std::vector<std::vector<int>>& chains, const PlateCurves& layer, int layer_index,
                                 LineWeights weights) {
  if (weights == LineWeights::by_strength) return widths_by_strength(chains, layer);
  const double by_layer = layer_index == 0 ? kHeavy : layer_index == 1 ? 1.0 : kLight;
  return std::vector<double>(chains.size(), layer.width_mm * (weights == LineWeights::by_layer ? by_layer : 1.0));
}

void emit(Plate& plate, std::vector<Vec2>& run, const PlateCurves& layer, double width_mm, double tol_mm) {
  if (run.size() >= 2) {
    std::vector<char> keep(run.size(), 0);
    keep.front() = keep.back() = 1;
    simplify(run, 0, run.size() - 1, tol_mm, keep);
    PlatePath path{{}, width_mm, layer.name};
    for (size_t k = 0; k < run.size(); ++k)
      if (keep[k]) path.points.push_back(run[k]);
    plate.paths.push_back(std::move(path));
  }
  run.clear();
}
}  // namespace

void add_visible_paths(Plate& plate, const PlateCurves& layer, int layer_index, const PageFrame& frame,
                       const DepthRaster& r, const PlateParams& params) {
  const double step_px = 0.5, tol_mm = params.simplify_px / r.px_per_mm;
  const std::vector<std::vector<int>> chains = chain_segments(int(layer.points.size()), layer.segments);
  const std::vector<double> widths = chain_widths(chains, layer, layer_index, params.weights);
  for (size_t c = 0; c < chains.size(); ++c) {
    const std::vector<int>& chain = chains[c];
    std::vector<Vec2> run;
    for (size_t k = 0; k + 1 < chain.size(); ++k) {
      const Vec3 &a = layer.points[size_t(chain[k])], &b = layer.points[size_t(chain[k + 1])];
      const double len_px = (frame.to_mm(b) - frame.to_mm(a)).norm() * r.px_per_mm;
      const int n = std::max(1, int(std::ceil(len_px / step_px)));
      const Vec3 middle = 0.5 * (a + b);
      (visible(middle, frame, r) ? plate.visible_segments
       : on_drawing(middle, frame, r) ? plate.hidden_segments : plate.outside_segments) += 1;
      for (int s = k == 0 ? 0 : 1; s <= n; ++s) {
        const Vec3 q = a + (b - a) * (double(s) / n);
        if (visible(q, frame, r)) run.push_back(frame.to_mm(q));
        else emit(plate, run, layer, widths[c], tol_mm);
      }
    }
    emit(plate, run, layer, widths[c], tol_mm);
  }
}

}  // namespace reliefkit
