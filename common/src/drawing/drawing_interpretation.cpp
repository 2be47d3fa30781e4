#include "reliefkit/drawing/drawing_interpretation.h"

#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>
#include <deque>
#include <limits>
#include <map>
#include <queue>
#include <numeric>
#include <set>
#include <tuple>

#include "reliefkit/base/scale.h"

namespace reliefkit {

void InterpretationParams::validate() const {
  require_range(margin, "Margin width (px)", 0.5, 1000);
  require_range(gap_close, "Gap closing (px)", 0, 1000);
  require_range(min_region_area, "Smallest region (px^2)", 0, 1e12);
}

namespace {

// The region at pixel p (rounded), -1 outside the image or on a curve.
int region_at(const cv::Mat& labels, const Vec2& p) {
  const int x = int(std::lround(p.x())), y = int(std::lround(p.y()));
  if (x < 0 || y < 0 || x >= labels.cols || y >= labels.rows) return -1;
  return labels.at<int>(y, x);
}

// Least samples for a pair of sides to count as a step of its curve (and at least a tenth of them).
constexpr int kMinPairSamples = 4;

}  // namespace

bool CurveOverride::is_step() const {
  if (spans.empty()) return true;
  for (const ProfileSpan& s : spans)
    if (s.profile == CurveProfile::Step) return true;
  return false;
}

DrawingInterpretation interpret_drawing(const DrawingCurves& dc, const InterpretationParams& p) {
  p.validate();
  const int nc = static_cast<int>(dc.curves.size());
  DrawingInterpretation out;
  out.profiles.assign(size_t(nc), {});
  out.is_step.assign(size_t(nc), 1);
  out.weight.assign(size_t(nc), 0);
  std::vector<CurveOverride::Direction> direction(size_t(nc), CurveOverride::Direction::Auto);
  std::vector<char> seen(size_t(nc), 0);
  for (const auto& f : p.overrides) {
    if (f.curve < 0 || f.curve >= nc)
      throw InputError("The interpretation names curve " + std::to_string(f.curve) + ", but the drawing has curves 0 to " +
                       std::to_string(nc - 1) + ".");
    if (seen[size_t(f.curve)]++) throw InputError("The interpretation names curve " + std::to_string(f.curve) + " twice.");
    if (f.weight < 0 || f.weight > 1000)
      throw InputError("The interpretation gives curve " + std::to_string(f.curve) + " the weight " + std::to_string(f.weight) +
                       "; weights are whole numbers from 0 (automatic) to 1000.");
    for (const ProfileSpan& sp : f.spans) {
      if (!(sp.from >= 0 && sp.to <= 1 && sp.from < sp.to))
        throw InputError("The interpretation gives curve " + std::to_string(f.curve) +
                         " a profile span that is not within 0 to 1 (from < to).");
      for (size_t i = 0; i < sp.shape.size(); ++i)
        if (!std::isfinite(sp.shape[i].x()) || !std::isfinite(sp.shape[i].y()) || sp.shape[i].x() < -1 || sp.shape[i].x() > 1 ||
            (i > 0 && !(sp.shape[i].x() > sp.shape[i - 1].x())))
          throw InputError("The interpretation gives curve " + std::to_string(f.curve) +
                           " a free-form shape whose t values are not increasing within -1 to 1.");
    }
    out.profiles[size_t(f.curve)] = f.spans;
    out.is_step[size_t(f.curve)] = f.is_step();
    out.weight[size_t(f.curve)] = f.weight;
    direction[size_t(f.curve)] = f.direction;
  }
  if (dc.width <= 0 || dc.height <= 0) return out;
  // Regions: the image minus the curves (drawn 2 px wide), 4-connected.
  cv::Mat ink(dc.height, dc.width, CV_8U, cv::Scalar(0));
  for (const auto& c : dc.curves) {
    std::vector<cv::Point> pts;
    for (const auto& q : c) pts.emplace_back(int(std::lround(q.x())), int(std::lround(q.y())));
    cv::polylines(ink, pts, false, cv::Scalar(255), 2, cv::LINE_8);
    // Line detection fades where curves meet (a junction's profile is no line's): each end is
    // extended along its direction, so that touching shapes close their regions.
    if (c.size() >= 2 && p.gap_close > 0)
      for (int e = 0; e < 2; ++e) {
        const Vec2 a = e ? c[c.size() - 1] : c[0];
        const Vec2 b = e ? c[std::max<size_t>(0, c.size() >= 4 ? c.size() - 4 : 0)] : c[std::min<size_t>(3, c.size() - 1)];
        Vec2 d = a - b;
        if (!(d.norm() > 0)) continue;
        d.normalize();
        const Vec2 z = a + p.gap_close * d;
        cv::line(ink, cv::Point(int(std::lround(a.x())), int(std::lround(a.y()))),
                 cv::Point(int(std::lround(z.x())), int(std::lround(z.y()))), cv::Scalar(255), 2, cv::LINE_8);
      }
  }
  cv::Mat free = ink == 0, labels;
  const int n = cv::connectedComponents(free, labels, 4, CV_32S);
  labels -= 1;  // the curves' label 0 becomes -1; regions 0 .. n-2
  out.regions = labels;
  out.region_count = std::max(0, n - 1);
  // Region areas, and which regions touch the image's border (the paper around the object).
  const int nr = out.region_count;
  std::vector<char> small(size_t(nr), 0), border(size_t(nr), 0);
  std::vector<long> area(size_t(nr), 0);
  {
    for (int y = 0; y < labels.rows; ++y) {
      const int* row = labels.ptr<int>(y);
      for (int x = 0; x < labels.cols; ++x)
        if (row[x] >= 0) {
          ++area[size_t(row[x])];
          if (x == 0 || y == 0 || x == labels.cols - 1 || y == labels.rows - 1) border[size_t(row[x])] = 1;
        }
    }
    // Specks between dots of stippling or strokes of hatching are shading, not parts of the relief.
    for (int r = 0; r < nr; ++r) small[size_t(r)] = area[size_t(r)] < p.min_region_area;
  }

  // Each curve's sides, by samples at `margin` beside it: the pair (left, right) most samples see,
  // and every pair enough samples see (a curve running past a junction has other regions beside
  // it along part of its length: each such pair is a step of its own in the graph).
  out.sides.assign(size_t(nc), {-1, -1});
  std::vector<std::vector<std::array<int, 2>>> pairs(static_cast<size_t>(nc));
  for (int k = 0; k < nc; ++k) {
    const auto& c = dc.curves[size_t(k)];
    std::map<std::array<int, 2>, int> votes;
    int samples = 0;
    for (size_t i = 0; i + 1 < c.size(); ++i) {
      Vec2 d = c[i + 1] - c[i];
      const double len = d.norm();
      if (!(len > 0)) continue;
      d /= len;
      const Vec2 l(d.y(), -d.x());  // left of the direction of travel, y down
      const Vec2 m = 0.5 * (c[i] + c[i + 1]);
      ++votes[{region_at(labels, m + p.margin * l), region_at(labels, m - p.margin * l)}];
      ++samples;
    }
    int best = 0;
    for (const auto& [pr, n] : votes) {
      const bool ok = pr[0] >= 0 && pr[1] >= 0 && pr[0] != pr[1] && !small[size_t(pr[0])] && !small[size_t(pr[1])];
      if (!ok) continue;
      if (n > best) best = n, out.sides[size_t(k)] = pr;
      if (n >= std::max(kMinPairSamples, samples / 10)) pairs[size_t(k)].push_back(pr);
    }
    if (best > 0 && pairs[size_t(k)].empty()) pairs[size_t(k)].push_back(out.sides[size_t(k)]);
  }

  // Ridges and valleys leave both their sides at one height: their sides are one node.
  std::vector<int> node(static_cast<size_t>(nr));
  std::iota(node.begin(), node.end(), 0);
  auto find = [&](int r) {
    while (node[size_t(r)] != r) r = node[size_t(r)] = node[size_t(node[size_t(r)])];
    return r;
  };
  for (int k = 0; k < nc; ++k)
    if (!out.is_step[size_t(k)])
      for (const auto& pr : pairs[size_t(k)]) node[size_t(find(pr[0]))] = find(pr[1]);
  // The graph: nodes, steps between two different nodes (neither of them a speck), each step at
  // least its weight; a fixed direction holds for every pair of sides of its curve.
  std::vector<std::map<int, int>> adj(static_cast<size_t>(nr));  // node -> (node -> least step)
  std::vector<std::vector<int>> lower_than(static_cast<size_t>(nr));  // fixed: node -> nodes that must be above it
  std::vector<int> fixed_in(size_t(nr), 0);
  for (int k = 0; k < nc; ++k) {
    if (pairs[size_t(k)].empty()) {
      ++out.ignored_curves;
      continue;
    }
    if (!out.is_step[size_t(k)]) continue;
    for (const auto& pr : pairs[size_t(k)]) {
      const int a = find(pr[0]), b = find(pr[1]), w = std::max(1, out.weight[size_t(k)]);
      if (a == b) continue;
      int& ab = adj[size_t(a)][b];
      ab = std::max(ab, w);
      int& ba = adj[size_t(b)][a];
      ba = std::max(ba, w);
      if (direction[size_t(k)] != CurveOverride::Direction::Auto) {
        const bool left_lower = direction[size_t(k)] == CurveOverride::Direction::LeftLower;
        const int lo = left_lower ? a : b, hi = left_lower ? b : a;
        lower_than[size_t(lo)].push_back(hi);
        ++fixed_in[size_t(hi)];
      }
    }
  }
  // Base: among the regions no fixed direction puts above another, the one bordering most curves.
  std::vector<int> dist(size_t(nr), -1);
  std::deque<int> q;
  auto start_from = [&](int r) {
    if (dist[size_t(r)] >= 0) return;
    dist[size_t(r)] = 0;
    q.push_back(r);
    out.base_regions.push_back(r);
    while (!q.empty()) {
      const int u = q.front();
      q.pop_front();
      for (const auto& [v, w] : adj[size_t(u)])
        if (dist[size_t(v)] < 0) dist[size_t(v)] = dist[size_t(u)] + 1, q.push_back(v);
    }
  };
  // The paper around the drawn object is the ground the relief stands on (unless the user asks for
  // the thesis' heuristic alone); then, per connected part of the graph, the thesis' base.
  if (p.paper_is_base)
    for (int r = 0; r < nr; ++r)
      if (border[size_t(r)] && !small[size_t(r)] && fixed_in[size_t(r)] == 0 && !adj[size_t(r)].empty()) start_from(r);
  for (;;) {  // one base per connected part of the graph
    int best = -1;
    for (int r = 0; r < nr; ++r)
      if (dist[size_t(r)] < 0 && !adj[size_t(r)].empty() && fixed_in[size_t(r)] == 0 &&
          (best < 0 || adj[size_t(r)].size() > adj[size_t(best)].size()))
        best = r;
    if (best < 0) {
      for (int r = 0; r < nr; ++r)
        if (dist[size_t(r)] < 0 && !adj[size_t(r)].empty()) best = r;
      if (best < 0) break;
    }
    start_from(best);
  }
  // A total order respecting the fixed directions (Kahn): nearest the base first; among regions as
  // near, the larger first, so that where two neighbours are as near the ground (a tool's body and
  // the small platform drawn at its top) the small one is the detail standing on the large one.
  std::vector<int> order, rank(size_t(nr), -1), in = fixed_in;
  using Item = std::tuple<int, long, int>;  // (distance from the base, -area, region)
  std::priority_queue<Item, std::vector<Item>, std::greater<Item>> ready;
  auto item = [&](int r) { return Item{std::max(0, dist[size_t(r)]), -area[size_t(r)], r}; };
  for (int r = 0; r < nr; ++r)
    if (in[size_t(r)] == 0) ready.push(item(r));
  while (!ready.empty()) {
    const int u = std::get<2>(ready.top());
    ready.pop();
    rank[size_t(u)] = int(order.size());
    order.push_back(u);
    for (int v : lower_than[size_t(u)])
      if (--in[size_t(v)] == 0) ready.push(item(v));
  }
  if (int(order.size()) < nr)
    throw InputError("The fixed step directions contradict each other: following them leads round a loop back to "
                     "a region below itself. Check the directions given in the interpretation file.");
  // Levels: the longest chain of steps below each node, every step going up the order.
  std::vector<int> level(size_t(nr), 0);
  for (int u : order)
    for (const auto& [v, w] : adj[size_t(u)])
      if (rank[size_t(v)] > rank[size_t(u)]) level[size_t(v)] = std::max(level[size_t(v)], level[size_t(u)] + w);
  // A region below all its neighbours that is not a base (one the user sank, say) sits as high as
  // its steps allow: one step below its lowest neighbour, not down on the ground.
  std::vector<char> is_base(size_t(nr), 0);
  for (int b : out.base_regions) is_base[size_t(b)] = 1;
  for (auto it = order.rbegin(); it != order.rend(); ++it) {
    const int u = *it;
    if (is_base[size_t(u)] || adj[size_t(u)].empty()) continue;
    int up = std::numeric_limits<int>::max();
    bool source = true;
    for (const auto& [v, w] : adj[size_t(u)]) {
      if (rank[size_t(v)] < rank[size_t(u)]) source = false;
      up = std::min(up, level[size_t(v)] - w);
    }
    if (source && up > level[size_t(u)]) level[size_t(u)] = up;
  }
  out.region_height.assign(size_t(nr), 0);
  for (int r = 0; r < nr; ++r) out.region_height[size_t(r)] = level[size_t(find(r))];
  out.step.assign(size_t(nc), 0);
  for (int k = 0; k < nc; ++k) {
    const auto [a, b] = out.sides[size_t(k)];
    if (a >= 0 && b >= 0) out.step[size_t(k)] = out.region_height[size_t(b)] - out.region_height[size_t(a)];
  }
  return out;
}

}  // namespace reliefkit
