#include "reliefkit/base/curve_selection.h"

#include "reliefkit/base/disjoint_sets.h"
#include "reliefkit/base/smoothing.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <tuple>
#include <unordered_map>

namespace reliefkit {

Polylines select_segments(const Polylines& in, const std::vector<char>& keep_segment) {
  Polylines out;
  out.rejected_faces = in.rejected_faces;
  std::vector<int> remap(in.points.size(), -1);
  for (size_t k = 0; k < in.segments.size(); ++k) {
    if (!keep_segment[k]) continue;
    std::array<int, 2> s;
    for (int e = 0; e < 2; ++e) {
      int p = in.segments[k][e];
      if (remap[p] < 0) {
        remap[p] = static_cast<int>(out.points.size());
        out.points.push_back(in.points[p]);
        out.strength.push_back(in.strength[p]);
        if (!in.point_edge.empty()) {
          out.point_edge.push_back(in.point_edge[p]);
          out.point_weight.push_back(in.point_weight[p]);
        }
      }
      s[e] = remap[p];
    }
    out.segments.push_back(s);
    out.segment_face.push_back(in.segment_face[k]);
  }
  return out;
}

double automatic_curve_threshold(double noise_scale, const Polylines& all) {
  std::vector<double> st;
  st.reserve(all.segments.size());
  for (const auto& sg : all.segments) st.push_back(0.5 * (all.strength[sg[0]] + all.strength[sg[1]]));
  return automatic_curve_threshold(noise_scale, std::move(st));
}

double automatic_curve_threshold(double noise_scale, std::vector<double> st) {
  // Segments of negative strength (a ridge where k1 < 0) are no candidates at all.
  st.erase(std::remove_if(st.begin(), st.end(), [](double x) { return !(x >= 0); }), st.end());
  double top = 0;
  if (!st.empty()) {
    auto k = st.begin() + static_cast<long>(kTopPercentile * double(st.size() - 1));
    std::nth_element(st.begin(), k, st.end());
    top = *k;
  }
  return std::max(kNoiseFactor * noise_scale, kTopFactor * top);
}

double median_positive(const std::vector<double>& values) {
  std::vector<double> s;
  s.reserve(values.size());
  for (double x : values)
    if (std::isfinite(x) && x > 0) s.push_back(x);
  if (s.empty()) return 0;
  auto mid = s.begin() + s.size() / 2;
  std::nth_element(s.begin(), mid, s.end());
  return *mid;
}

Polylines keep_strong_segments(const Polylines& in, double min_strength) {
  std::vector<char> keep(in.segments.size());
  for (size_t k = 0; k < in.segments.size(); ++k)
    keep[k] = 0.5 * (in.strength[in.segments[k][0]] + in.strength[in.segments[k][1]]) >= min_strength;
  return select_segments(in, keep);
}

Polylines drop_short_chains(const Polylines& in, double min_length) {
  if (!(min_length > 0)) return in;
  std::vector<char> keep_point(in.points.size(), 0);
  for (const auto& ch : in.chains()) {
    double L = 0;
    for (size_t k = 1; k < ch.size(); ++k) L += (in.points[ch[k]] - in.points[ch[k - 1]]).norm();
    if (L >= min_length)
      for (int p : ch) keep_point[p] = 1;
  }
  std::vector<char> keep(in.segments.size());
  for (size_t k = 0; k < in.segments.size(); ++k)
    keep[k] = keep_point[in.segments[k][0]] && keep_point[in.segments[k][1]];
  return select_segments(in, keep);
}

namespace {

// A bridge `d` from an end (outward direction a) to another (outward direction b, facing it)
// follows the line when it leaves both ends within the turn, or when it is a jog: a small step
// sideways (at most `jog`, mesh units) where the line is broken and shifted, the ends overlapping
// by at most as much.
bool bridge_follows_line(const Vec3& a, const Vec3& b, const Vec3& d, double cos_turn, double jog) {
  const double dist = d.norm();
  if (!(dist > 0)) return true;
  if (a.dot(d) >= cos_turn * dist && b.dot(-d) >= cos_turn * dist) return true;
  const Vec3 along = (a - b).normalized();
  const double forward = along.dot(d);
  return forward >= -jog && (d - forward * along).norm() <= jog;
}

// An end of an open chain: its point, its chain and the outward direction near it.
struct ChainEnd {
  int point, chain;
  Vec3 out;
};

// The ends of the open chains (points with one segment), each direction taken over the last
// `max_gap` of its chain; and every chain's length.
std::vector<ChainEnd> chain_ends(const Polylines& c, const std::vector<int>& degree, double max_gap,
                                 std::vector<double>& chain_length) {
  std::vector<ChainEnd> ends;
  const auto chains = c.chains();
  for (int ci = 0; ci < static_cast<int>(chains.size()); ++ci) {
    const auto& ch = chains[ci];
    double length = 0;
    for (size_t i = 1; i < ch.size(); ++i) length += (c.points[ch[i]] - c.points[ch[i - 1]]).norm();
    chain_length.push_back(length);
    if (ch.size() < 2 || ch.front() == ch.back()) continue;
    const int n = static_cast<int>(ch.size());
    for (int side = 0; side < 2; ++side) {
      const int p = side == 0 ? ch.front() : ch.back();
      if (degree[p] != 1) continue;
      Vec3 back = c.points[p];
      double walked = 0;
      for (int i = 1; i < n && walked < max_gap; ++i) {
        const Vec3& q = c.points[side == 0 ? ch[i] : ch[n - 1 - i]];
        walked += (q - back).norm();
        back = q;
      }
      const Vec3 out = c.points[p] - back;
      if (out.norm() > 0) ends.push_back({p, ci, out.normalized()});
    }
  }
  return ends;
}

// The pairs of ends a bridge may join (distance, i, j with i < j), through a grid of cell max_gap.
std::vector<std::tuple<double, int, int>> bridge_candidates(const Polylines& c, const std::vector<ChainEnd>& ends,
                                                            const std::vector<double>& chain_length, double max_gap,
                                                            double max_turn) {
  // Cell indices clamped: a coordinate 1e30 times the gap must not overflow the integer (fuzzer).
  auto index = [max_gap](double v) {
    const double q = std::floor(v / max_gap);
    return static_cast<long long>(q == q ? std::clamp(q, -1e15, 1e15) : 0.0);
  };
  auto cell = [&index](const Vec3& x) { return std::array<long long, 3>{index(x.x()), index(x.y()), index(x.z())}; };
  std::vector<std::pair<std::array<long long, 3>, int>> grid;
  for (int i = 0; i < static_cast<int>(ends.size()); ++i) grid.push_back({cell(c.points[ends[i].point]), i});
  std::sort(grid.begin(), grid.end());
  const double cos_turn = std::cos(max_turn);
  std::vector<std::tuple<double, int, int>> pairs;
  for (int i = 0; i < static_cast<int>(ends.size()); ++i) {
    const Vec3& pi = c.points[ends[i].point];
    const auto ci = cell(pi);
    for (long long dx = -1; dx <= 1; ++dx)
      for (long long dy = -1; dy <= 1; ++dy)
        for (long long dz = -1; dz <= 1; ++dz) {
          const std::array<long long, 3> key{ci[0] + dx, ci[1] + dy, ci[2] + dz};
          for (auto it = std::lower_bound(grid.begin(), grid.end(), std::make_pair(key, -1)); it != grid.end() && it->first == key; ++it) {
            const int j = it->second;
            const Vec3 d = c.points[ends[j].point] - pi;
            if (j <= i || !(d.norm() <= max_gap)) continue;
            if (ends[i].chain == ends[j].chain && chain_length[ends[i].chain] <= 4 * max_gap) continue;
            if (ends[i].out.dot(-ends[j].out) < cos_turn) continue;  // the two ends must face each other
            if (!bridge_follows_line(ends[i].out, ends[j].out, d, cos_turn, kJogShare * max_gap)) continue;
            pairs.emplace_back(d.norm(), i, j);
          }
        }
  }
  return pairs;
}

}  // namespace

int link_gaps(Polylines& c, double max_gap, double max_turn) {
  if (!(max_gap > 0) || c.segments.empty()) return 0;
  const int np = static_cast<int>(c.points.size());
  std::vector<int> degree(np, 0), seg_of(np, -1);
  for (int k = 0; k < static_cast<int>(c.segments.size()); ++k)
    for (int e : c.segments[k]) ++degree[e], seg_of[e] = k;
  std::vector<double> chain_length;
  const std::vector<ChainEnd> ends = chain_ends(c, degree, max_gap, chain_length);
  if (ends.size() < 2) return 0;
  std::vector<std::tuple<double, int, int>> pairs = bridge_candidates(c, ends, chain_length, max_gap, max_turn);
  std::sort(pairs.begin(), pairs.end());  // nearest first, each end at most once
  std::vector<char> used(ends.size(), 0);
  int links = 0;
  for (const auto& [dist, i, j] : pairs) {
    if (used[i] || used[j]) continue;
    used[i] = used[j] = 1;
    const int a = ends[i].point, b = ends[j].point;
    c.segments.push_back({a, b});
    c.segment_face.push_back(c.segment_face[seg_of[a]]);
    ++links;
  }
  return links;
}

Polylines hysteresis(const Polylines& all, const std::vector<char>& strong, const std::vector<char>& weak) {
  const size_t ns = all.segments.size();
  std::vector<std::vector<int>> at_point(all.points.size());
  for (size_t k = 0; k < ns; ++k)
    for (int e = 0; e < 2; ++e) at_point[all.segments[k][e]].push_back(int(k));
  std::vector<char> keep(ns, 0);
  std::vector<int> stack;
  for (size_t k = 0; k < ns; ++k)
    if (strong[k] && !keep[k]) {
      keep[k] = 1;
      stack.push_back(int(k));
      while (!stack.empty()) {
        const int s = stack.back();
        stack.pop_back();
        for (int e = 0; e < 2; ++e)
          for (int o : at_point[all.segments[s][e]])
            if (!keep[o] && (weak[o] || strong[o])) keep[o] = 1, stack.push_back(o);
      }
    }
  return select_segments(all, keep);
}

namespace {

Vec3 segment_midpoint(const Polylines& p, size_t k) {
  return 0.5 * (p.points[p.segments[k][0]] + p.points[p.segments[k][1]]);
}

double distance_to_segment(const Vec3& x, const Vec3& a, const Vec3& b) {
  const Vec3 d = b - a;
  const double len2 = d.squaredNorm();
  const double t = len2 > 0 ? std::clamp((x - a).dot(d) / len2, 0.0, 1.0) : 0.0;
  return (a + t * d - x).norm();
}

// The segments of a curve set filed by their midpoints in a uniform grid whose cells are at least
// twice the query radius and the longest segment: every segment within the radius of a point is
// in the point's cell or a neighbouring one.
class SegmentGrid {
 public:
  SegmentGrid(const Polylines& p, double radius) : p_(p), radius_(radius), cell_(2 * radius) {
    for (const auto& s : p.segments) cell_ = std::max(cell_, (p.points[s[1]] - p.points[s[0]]).norm());
    for (size_t k = 0; k < p.segments.size(); ++k) cells_[key(cell_of(segment_midpoint(p, k)))].push_back(int(k));
  }
  bool near(const Vec3& x) const {
    const std::array<long, 3> c = cell_of(x);
    for (long i = c[0] - 1; i <= c[0] + 1; ++i)
      for (long j = c[1] - 1; j <= c[1] + 1; ++j)
        for (long k = c[2] - 1; k <= c[2] + 1; ++k) {
          const auto it = cells_.find(key({i, j, k}));
          if (it == cells_.end()) continue;
          for (int s : it->second)
            if (distance_to_segment(x, p_.points[p_.segments[s][0]], p_.points[p_.segments[s][1]]) <= radius_)
              return true;
        }
    return false;
  }

 private:
  std::array<long, 3> cell_of(const Vec3& x) const {
    return {long(std::floor(x.x() / cell_)), long(std::floor(x.y() / cell_)), long(std::floor(x.z() / cell_))};
  }
  static std::uint64_t key(const std::array<long, 3>& c) {
    auto bits = [](long v) { return static_cast<std::uint64_t>(v) & 0x1fffffu; };
    return (bits(c[0]) << 42) | (bits(c[1]) << 21) | bits(c[2]);
  }
  const Polylines& p_;
  double radius_, cell_;
  std::unordered_map<std::uint64_t, std::vector<int>> cells_;
};

}  // namespace

std::vector<char> segments_near(const Polylines& curves, const Polylines& others, double radius) {
  std::vector<char> near(curves.segments.size(), 0);
  if (others.segments.empty() || !(radius > 0)) return near;
  const SegmentGrid grid(others, radius);
  const long n = static_cast<long>(curves.segments.size());
#pragma omp parallel for schedule(dynamic, 1024)
  for (long k = 0; k < n; ++k) near[k] = grid.near(segment_midpoint(curves, size_t(k)));
  return near;
}

void append_curves(Polylines& curves, const Polylines& more) {
  const int offset = static_cast<int>(curves.points.size());
  curves.points.insert(curves.points.end(), more.points.begin(), more.points.end());
  curves.strength.insert(curves.strength.end(), more.strength.begin(), more.strength.end());
  curves.point_edge.insert(curves.point_edge.end(), more.point_edge.begin(), more.point_edge.end());
  curves.point_weight.insert(curves.point_weight.end(), more.point_weight.begin(), more.point_weight.end());
  for (const auto& s : more.segments) curves.segments.push_back({s[0] + offset, s[1] + offset});
  curves.segment_face.insert(curves.segment_face.end(), more.segment_face.begin(), more.segment_face.end());
  curves.rejected_faces += more.rejected_faces;
}

std::vector<int> curve_pieces(const Polylines& c, std::vector<double>& lengths) {
  DisjointSets sets(static_cast<int>(c.points.size()));
  for (const auto& s : c.segments) sets.unite(s[0], s[1]);
  int count = 0;
  const std::vector<int> piece_of_point = std::move(sets).numbered(count);
  std::vector<int> piece(c.segments.size());
  lengths.assign(size_t(count), 0.0);
  for (size_t k = 0; k < c.segments.size(); ++k) {
    piece[k] = piece_of_point[size_t(c.segments[k][0])];
    lengths[size_t(piece[k])] += (c.points[c.segments[k][1]] - c.points[c.segments[k][0]]).norm();
  }
  return piece;
}

Polylines drop_dashes(const Polylines& c, double min_length) {
  if (!(min_length > 0) || c.segments.empty()) return c;
  std::vector<double> lengths;
  const std::vector<int> piece = curve_pieces(c, lengths);
  std::vector<char> keep(c.segments.size());
  for (size_t k = 0; k < c.segments.size(); ++k) keep[k] = lengths[size_t(piece[k])] >= min_length;
  return select_segments(c, keep);
}

std::vector<double> local_contrast(const Surface& surface, const std::vector<double>& x, double radius) {
  std::vector<double> mean = x;
  diffuse(surface, radius, mean);
  std::vector<double> spread(x.size());
  for (size_t v = 0; v < x.size(); ++v) spread[v] = std::abs(x[v] - mean[v]);
  diffuse(surface, radius, spread);
  std::vector<double> contrast(x.size(), 0.0);
  for (size_t v = 0; v < x.size(); ++v)
    if (spread[v] > 0) contrast[v] = (x[v] - mean[v]) / spread[v];
  return contrast;
}

std::vector<double> contrast_weights(const Polylines& c, const std::vector<double>& contrast) {
  std::vector<double> w = interpolate_at_points(c, contrast);
  for (double& x : w) x = std::clamp(x / kLineContrast, 0.0, 1.0);
  return w;
}

Polylines select_lines(const Polylines& all, double threshold, const LineLinking& linking, double edge,
                       double min_length, const std::vector<double>& contrast) {
  const std::vector<double> seed_weight = contrast.empty() ? std::vector<double>{} : contrast_weights(all, contrast);
  std::vector<char> strong(all.segments.size()), weak(all.segments.size());
  for (size_t k = 0; k < all.segments.size(); ++k) {
    const int a = all.segments[k][0], b = all.segments[k][1];
    const double s = 0.5 * (all.strength[a] + all.strength[b]);
    const double w = seed_weight.empty() ? 1.0 : 0.5 * (seed_weight[a] + seed_weight[b]);
    strong[k] = s * w >= threshold;
    weak[k] = s >= linking.weak_ratio * threshold;
  }
  return connect_lines(all, strong, weak, linking.gap_edges * edge, min_length);
}

Polylines connect_lines(const Polylines& all, const std::vector<char>& strong, const std::vector<char>& weak,
                        double max_gap, double min_length, int* links) {
  Polylines kept = hysteresis(all, strong, weak);
  const int made = link_gaps(kept, max_gap, kLinkTurn);
  if (links) *links = made;
  return drop_dashes(kept, min_length);
}

CurveStatistics curve_statistics(const Polylines& c, double edge, long long faces) {
  CurveStatistics st;
  std::vector<double> lengths;
  const std::vector<int> piece = curve_pieces(c, lengths);
  std::vector<char> used(lengths.size(), 0);  // pieces of isolated points (no segment) are not drawn
  for (int p : piece) used[size_t(p)] = 1;
  for (size_t p = 0; p < lengths.size(); ++p) {
    if (!used[p]) continue;
    ++st.pieces;
    st.length += lengths[p];
    if (lengths[p] < kDashEdges * edge) ++st.dashes, st.dash_length += lengths[p];
  }
  if (edge > 0 && faces > 0) st.length_per_kface = st.length / edge / (double(faces) / 1000.0);
  return st;
}

}  // namespace reliefkit
