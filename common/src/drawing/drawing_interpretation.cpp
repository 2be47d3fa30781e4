#include "reliefkit/drawing/drawing_interpretation.h"

#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <unordered_map>
#include <cmath>
#include <deque>
#include <limits>
#include <map>
#include <queue>
#include <numeric>
#include <set>
#include <sstream>
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

// A curve the user's interpretation says something about is structure, whatever it looks like.
bool direction_or_profile_given(const std::vector<CurveOverride>& overrides, int k) {
  for (const CurveOverride& f : overrides)
    if (f.curve == k) return true;
  return false;
}

}  // namespace

bool CurveOverride::is_step() const {
  if (spans.empty()) return true;
  for (const ProfileSpan& s : spans)
    if (s.profile == CurveProfile::Step) return true;
  return false;
}

namespace {

// A user override checked against the drawing: a known curve, named once, a sane weight and spans.
void check_override(const CurveOverride& f, int nc, std::vector<char>& seen) {
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
}

// The overrides' profiles, steps and weights into `out`; their directions per curve.
std::vector<CurveOverride::Direction> apply_overrides(const std::vector<CurveOverride>& overrides, int nc,
                                                      DrawingInterpretation& out) {
  out.profiles.assign(size_t(nc), {});
  out.is_step.assign(size_t(nc), 1);
  out.weight.assign(size_t(nc), 0);
  std::vector<CurveOverride::Direction> direction(size_t(nc), CurveOverride::Direction::Auto);
  std::vector<char> seen(size_t(nc), 0);
  for (const auto& f : overrides) {
    check_override(f, nc, seen);
    out.profiles[size_t(f.curve)] = f.spans;
    out.is_step[size_t(f.curve)] = f.is_step();
    out.weight[size_t(f.curve)] = f.weight;
    direction[size_t(f.curve)] = f.direction;
  }
  return direction;
}

// How far an end of curve k is extended: `gap_close`, or 1.25 x its line's width + 1.5 px (2.5 sigma
// + 1.5, over which line detection fades at a junction) for a wider line.
double end_reach(const DrawingCurves& dc, size_t k, double gap_close) {
  return k < dc.line_width.size() ? std::max(gap_close, 1.25 * dc.line_width[k] + 1.5) : gap_close;
}

cv::Point pixel_of(const Vec2& q) { return cv::Point(int(std::lround(q.x())), int(std::lround(q.y()))); }

// Ends of different curves within reach of each other (the smaller reach) joined by a segment: two
// extensions aimed past each other at a junction would leave a gap (grid of cell `cell`).
void bridge_near_ends(cv::Mat& ink, const std::vector<std::pair<Vec2, double>>& ends, const std::vector<size_t>& owner,
                      double cell) {
  std::unordered_map<long long, std::vector<size_t>> grid;
  auto key = [&](double x, double y) { return (long long)std::floor(x / cell) * 1000003LL + (long long)std::floor(y / cell); };
  for (size_t i = 0; i < ends.size(); ++i) grid[key(ends[i].first.x(), ends[i].first.y())].push_back(i);
  for (size_t i = 0; i < ends.size(); ++i)
    for (int ox = -1; ox <= 1; ++ox)
      for (int oy = -1; oy <= 1; ++oy) {
        const auto it = grid.find(key(ends[i].first.x() + ox * cell, ends[i].first.y() + oy * cell));
        if (it == grid.end()) continue;
        for (size_t j : it->second)
          if (j > i && owner[j] != owner[i] &&
              (ends[i].first - ends[j].first).norm() <= std::min(ends[i].second, ends[j].second))
            cv::line(ink, pixel_of(ends[i].first), pixel_of(ends[j].first), cv::Scalar(255), 2, cv::LINE_8);
      }
}

// The structure curves (shading left out) drawn 2 px wide. Line detection fades where curves meet (a junction's profile is no
// line's): each end is extended along its direction by its reach (end_reach), and ends within reach
// of each other are joined, so that touching shapes close their regions.
cv::Mat curve_ink(const DrawingCurves& dc, double gap_close, const std::vector<char>& shading) {
  cv::Mat ink(dc.height, dc.width, CV_8U, cv::Scalar(0));
  std::vector<std::pair<Vec2, double>> ends;
  std::vector<size_t> owner;
  double cell = 1;
  for (size_t k = 0; k < dc.curves.size(); ++k) {
    if (shading[k]) continue;
    const auto& c = dc.curves[k];
    std::vector<cv::Point> pts;
    for (const auto& q : c) pts.push_back(pixel_of(q));
    cv::polylines(ink, pts, false, cv::Scalar(255), 2, cv::LINE_8);
    if (c.size() < 2 || !(gap_close > 0)) continue;
    const double reach = end_reach(dc, k, gap_close);
    for (int e = 0; e < 2; ++e) {
      const Vec2 a = e ? c[c.size() - 1] : c[0];
      const Vec2 b = e ? c[std::max<size_t>(0, c.size() >= 4 ? c.size() - 4 : 0)] : c[std::min<size_t>(3, c.size() - 1)];
      ends.emplace_back(a, reach), owner.push_back(k), cell = std::max(cell, reach);
      Vec2 d = a - b;
      if (!(d.norm() > 0)) continue;
      d.normalize();
      cv::line(ink, pixel_of(a), pixel_of(a + reach * d), cv::Scalar(255), 2, cv::LINE_8);
    }
  }
  bridge_near_ends(ink, ends, owner, cell);
  return ink;
}

// Per region: its area, whether it touches the image's border (the paper around the object), and
// whether it is a speck (between dots of stippling or strokes of hatching: shading, not relief).
struct RegionStats {
  std::vector<long> area;
  std::vector<char> border, small;
};

RegionStats region_stats(const cv::Mat& labels, int nr, double min_area) {
  RegionStats s{std::vector<long>(size_t(nr), 0), std::vector<char>(size_t(nr), 0), std::vector<char>(size_t(nr), 0)};
  for (int y = 0; y < labels.rows; ++y) {
    const int* row = labels.ptr<int>(y);
    for (int x = 0; x < labels.cols; ++x)
      if (row[x] >= 0) {
        ++s.area[size_t(row[x])];
        if (x == 0 || y == 0 || x == labels.cols - 1 || y == labels.rows - 1) s.border[size_t(row[x])] = 1;
      }
  }
  for (int r = 0; r < nr; ++r) s.small[size_t(r)] = s.area[size_t(r)] < min_area;
  return s;
}

// A curve's sides, by samples at `margin` beside it: the pair (left, right) most samples see
// (`sides`), and every pair enough samples see (returned: a curve running past a junction has
// other regions beside it along part of its length; each such pair is a step of its own).
std::vector<std::array<int, 2>> curve_sides(const std::vector<Vec2>& c, const cv::Mat& labels, const RegionStats& st,
                                            double margin, std::array<int, 2>& sides) {
  std::map<std::array<int, 2>, int> votes;
  int samples = 0;
  for (size_t i = 0; i + 1 < c.size(); ++i) {
    Vec2 d = c[i + 1] - c[i];
    const double len = d.norm();
    if (!(len > 0)) continue;
    d /= len;
    const Vec2 l(d.y(), -d.x());  // left of the direction of travel, y down
    const Vec2 m = 0.5 * (c[i] + c[i + 1]);
    ++votes[{region_at(labels, m + margin * l), region_at(labels, m - margin * l)}];
    ++samples;
  }
  std::vector<std::array<int, 2>> pairs;
  int best = 0;
  for (const auto& [pr, n] : votes) {
    const bool ok = pr[0] >= 0 && pr[1] >= 0 && pr[0] != pr[1] && !st.small[size_t(pr[0])] && !st.small[size_t(pr[1])];
    if (!ok) continue;
    if (n > best) best = n, sides = pr;
    if (n >= std::max(kMinPairSamples, samples / 10)) pairs.push_back(pr);
  }
  if (best > 0 && pairs.empty()) pairs.push_back(sides);
  return pairs;
}

// The graph of sect. 7.3: nodes are regions (the two sides of a ridge or valley merged into one),
// edges the steps between them with their least height, and the directions the user fixed.
struct RegionGraph {
  std::vector<int> node;                // union-find: region -> its node
  std::vector<std::map<int, int>> adj;  // node -> (node -> least step)
  std::vector<std::vector<int>> lower_than;  // fixed: node -> nodes that must be above it
  std::vector<int> fixed_in;            // fixed directions pointing up into each node
  int find(int r) {
    while (node[size_t(r)] != r) r = node[size_t(r)] = node[size_t(node[size_t(r)])];
    return r;
  }
};

RegionGraph region_graph(int nr, const std::vector<std::vector<std::array<int, 2>>>& pairs,
                         const std::vector<CurveOverride::Direction>& direction, DrawingInterpretation& out) {
  RegionGraph g{std::vector<int>(size_t(nr)), std::vector<std::map<int, int>>(size_t(nr)),
                std::vector<std::vector<int>>(size_t(nr)), std::vector<int>(size_t(nr), 0)};
  std::iota(g.node.begin(), g.node.end(), 0);
  const int nc = int(pairs.size());
  for (int k = 0; k < nc; ++k)  // ridges and valleys leave both their sides at one height
    if (!out.is_step[size_t(k)])
      for (const auto& pr : pairs[size_t(k)]) g.node[size_t(g.find(pr[0]))] = g.find(pr[1]);
  for (int k = 0; k < nc; ++k) {
    if (out.shading[size_t(k)]) continue;
    if (pairs[size_t(k)].empty()) {
      ++out.ignored_curves;
      continue;
    }
    if (!out.is_step[size_t(k)]) continue;
    for (const auto& pr : pairs[size_t(k)]) {  // a fixed direction holds for every pair of sides
      const int a = g.find(pr[0]), b = g.find(pr[1]), w = std::max(1, out.weight[size_t(k)]);
      if (a == b) continue;
      int& ab = g.adj[size_t(a)][b];
      ab = std::max(ab, w);
      int& ba = g.adj[size_t(b)][a];
      ba = std::max(ba, w);
      if (direction[size_t(k)] == CurveOverride::Direction::Auto) continue;
      const bool left_lower = direction[size_t(k)] == CurveOverride::Direction::LeftLower;
      g.lower_than[size_t(left_lower ? a : b)].push_back(left_lower ? b : a);
      ++g.fixed_in[size_t(left_lower ? b : a)];
    }
  }
  return g;
}

// The bases (into out.base_regions) and each node's breadth-first distance from them: the paper
// around the drawn object first (unless the user asks for the thesis' heuristic alone), then per
// connected part of the graph the thesis' base: among the regions no fixed direction puts above
// another, the one bordering most curves.
std::vector<int> distances_from_bases(const RegionGraph& g, const RegionStats& st, bool paper_is_base,
                                      DrawingInterpretation& out) {
  const int nr = int(g.adj.size());
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
      for (const auto& [v, w] : g.adj[size_t(u)])
        if (dist[size_t(v)] < 0) dist[size_t(v)] = dist[size_t(u)] + 1, q.push_back(v);
    }
  };
  if (paper_is_base)
    for (int r = 0; r < nr; ++r)
      if (st.border[size_t(r)] && !st.small[size_t(r)] && g.fixed_in[size_t(r)] == 0 && !g.adj[size_t(r)].empty()) start_from(r);
  for (;;) {
    int best = -1;
    for (int r = 0; r < nr; ++r)
      if (dist[size_t(r)] < 0 && !g.adj[size_t(r)].empty() && g.fixed_in[size_t(r)] == 0 &&
          (best < 0 || g.adj[size_t(r)].size() > g.adj[size_t(best)].size()))
        best = r;
    if (best < 0) {
      for (int r = 0; r < nr; ++r)
        if (dist[size_t(r)] < 0 && !g.adj[size_t(r)].empty()) best = r;
      if (best < 0) break;
    }
    start_from(best);
  }
  return dist;
}

// A total order respecting the fixed directions (Kahn): nearest the base first; among regions as
// near, the larger first, so that where two neighbours are as near the ground (a tool's body and
// the small platform drawn at its top) the small one is the detail standing on the large one.
std::vector<int> region_order(const RegionGraph& g, const std::vector<int>& dist, const std::vector<long>& area) {
  const int nr = int(g.adj.size());
  std::vector<int> order, in = g.fixed_in;
  using Item = std::tuple<int, long, int>;  // (distance from the base, -area, region)
  std::priority_queue<Item, std::vector<Item>, std::greater<Item>> ready;
  auto item = [&](int r) { return Item{std::max(0, dist[size_t(r)]), -area[size_t(r)], r}; };
  for (int r = 0; r < nr; ++r)
    if (in[size_t(r)] == 0) ready.push(item(r));
  while (!ready.empty()) {
    const int u = std::get<2>(ready.top());
    ready.pop();
    order.push_back(u);
    for (int v : g.lower_than[size_t(u)])
      if (--in[size_t(v)] == 0) ready.push(item(v));
  }
  if (int(order.size()) < nr)
    throw InputError("The fixed step directions contradict each other: following them leads round a loop back to "
                     "a region below itself. Check the directions given in the interpretation file.");
  return order;
}

// Levels: the longest chain of steps below each node, every step going up the order. A node below
// all its neighbours that is not a base (one the user sank, say) sits as high as its steps allow:
// one step below its lowest neighbour, not down on the ground.
std::vector<int> node_levels(const RegionGraph& g, const std::vector<int>& order, const std::vector<int>& bases) {
  const int nr = int(g.adj.size());
  std::vector<int> rank(size_t(nr), -1), level(size_t(nr), 0);
  for (size_t i = 0; i < order.size(); ++i) rank[size_t(order[i])] = int(i);
  for (int u : order)
    for (const auto& [v, w] : g.adj[size_t(u)])
      if (rank[size_t(v)] > rank[size_t(u)]) level[size_t(v)] = std::max(level[size_t(v)], level[size_t(u)] + w);
  std::vector<char> is_base(size_t(nr), 0);
  for (int b : bases) is_base[size_t(b)] = 1;
  for (auto it = order.rbegin(); it != order.rend(); ++it) {
    const int u = *it;
    if (is_base[size_t(u)] || g.adj[size_t(u)].empty()) continue;
    int up = std::numeric_limits<int>::max();
    bool source = true;
    for (const auto& [v, w] : g.adj[size_t(u)]) {
      if (rank[size_t(v)] < rank[size_t(u)]) source = false;
      up = std::min(up, level[size_t(v)] - w);
    }
    if (source && up > level[size_t(u)]) level[size_t(u)] = up;
  }
  return level;
}

}  // namespace

DrawingInterpretation interpret_drawing(const DrawingCurves& dc, const InterpretationParams& p) {
  p.validate();
  const int nc = static_cast<int>(dc.curves.size());
  DrawingInterpretation out;
  const auto direction = apply_overrides(p.overrides, nc, out);
  out.shading.assign(size_t(nc), 0);
  if (dc.width <= 0 || dc.height <= 0) return out;
  if (dc.shading.size() == size_t(nc))
    for (int k = 0; k < nc; ++k)
      if (dc.shading[size_t(k)] && !direction_or_profile_given(p.overrides, k)) out.shading[size_t(k)] = 1, ++out.shading_curves;
  // Regions: the image minus the structure curves, 4-connected.
  cv::Mat free = curve_ink(dc, p.gap_close, out.shading) == 0, labels;
  const int n = cv::connectedComponents(free, labels, 4, CV_32S);
  labels -= 1;  // the curves' label 0 becomes -1; regions 0 .. n-2
  out.regions = labels;
  out.region_count = std::max(0, n - 1);
  const int nr = out.region_count;
  const RegionStats st = region_stats(labels, nr, p.min_region_area);
  out.sides.assign(size_t(nc), {-1, -1});
  std::vector<std::vector<std::array<int, 2>>> pairs(static_cast<size_t>(nc));
  for (int k = 0; k < nc; ++k)
    if (!out.shading[size_t(k)]) pairs[size_t(k)] = curve_sides(dc.curves[size_t(k)], labels, st, p.margin, out.sides[size_t(k)]);
  RegionGraph g = region_graph(nr, pairs, direction, out);
  const std::vector<int> dist = distances_from_bases(g, st, p.paper_is_base, out);
  const std::vector<int> order = region_order(g, dist, st.area);
  const std::vector<int> level = node_levels(g, order, out.base_regions);
  out.region_height.assign(size_t(nr), 0);
  for (int r = 0; r < nr; ++r) out.region_height[size_t(r)] = level[size_t(g.find(r))];
  out.step.assign(size_t(nc), 0);
  for (int k = 0; k < nc; ++k) {
    const auto [a, b] = out.sides[size_t(k)];
    if (a >= 0 && b >= 0) out.step[size_t(k)] = out.region_height[size_t(b)] - out.region_height[size_t(a)];
  }
  return out;
}

int rising_regions(const DrawingInterpretation& di) {
  return static_cast<int>(std::count_if(di.region_height.begin(), di.region_height.end(), [](int h) { return h > 0; }));
}

void require_rising_regions(const DrawingCurves& curves, const DrawingInterpretation& di, double line_scale_px) {
  if (rising_regions(di) > 0) return;
  const int nc = static_cast<int>(curves.curves.size());
  std::ostringstream msg;
  msg << "No region of the drawing rises above the ground, so the relief would be a flat plane: " << nc
      << " curves, " << di.region_count << " regions, " << di.ignored_curves << " of the curves between no two regions";
  if (di.shading_curves > 0)
    msg << ", " << di.shading_curves << " recognised as shading (hatching: families of near-parallel strokes, left "
           "out of the regions; if they are the object's lines, untick Recognise shading)";
  if (di.ignored_curves > 0 && di.ignored_curves * 2 >= nc - di.shading_curves)
    msg << " (their ends are free: hatching, stippling or sketch strokes — or the two edges of an outline thicker "
           "than the line scale"
        << (line_scale_px > 0 ? " of " + std::to_string(int(std::lround(line_scale_px))) + " px" : std::string())
        << ", traced as separate lines)";
  msg << ". What to change: " << (line_scale_px > 0 ? "the automatic Line scale (0), or " : "")
      << "a Line scale of about half the width of the drawing's lines in pixels (thin lines in a small image: 1; an "
         "8-px pen: 4); or close the gaps in broken outlines; or give the steps in an interpretation file.";
  throw InputError(msg.str());
}

std::vector<FlatObject> flat_objects(const DrawingCurves& curves, const DrawingInterpretation& di, double min_share) {
  std::vector<FlatObject> flat;
  if (curves.objects.empty() || curves.objects.size() != di.regions.size()) return flat;
  cv::Mat labels, stats, centroids;
  const int n = cv::connectedComponentsWithStats(curves.objects, labels, stats, centroids, 8, CV_32S);
  std::vector<long> inside(size_t(n), 0), ground(size_t(n), 0);
  for (int y = 0; y < labels.rows; ++y)
    for (int x = 0; x < labels.cols; ++x) {
      const int l = labels.at<int>(y, x), r = di.regions.at<int>(y, x);
      if (l <= 0 || r < 0 || r >= int(di.region_height.size())) continue;
      ++inside[size_t(l)], ground[size_t(l)] += di.region_height[size_t(r)] == 0;
    }
  int largest = 0;
  for (int l = 1; l < n; ++l) largest = std::max(largest, stats.at<int>(l, cv::CC_STAT_AREA));
  for (int l = 1; l < n; ++l) {  // labels and marks beside the objects aside
    if (stats.at<int>(l, cv::CC_STAT_AREA) < std::max(400.0, 0.02 * largest) || inside[size_t(l)] == 0) continue;
    const double share = double(ground[size_t(l)]) / double(inside[size_t(l)]);
    if (share > min_share)
      flat.push_back({cv::Rect(stats.at<int>(l, cv::CC_STAT_LEFT), stats.at<int>(l, cv::CC_STAT_TOP),
                               stats.at<int>(l, cv::CC_STAT_WIDTH), stats.at<int>(l, cv::CC_STAT_HEIGHT)),
                      share});
  }
  return flat;
}

}  // namespace reliefkit
