#include "reliefkit/base/zero_crossings.h"

#include <tuple>

#include <algorithm>
#include <cmath>
#include <cstdint>

#ifdef _OPENMP
#include <omp.h>
#endif

namespace reliefkit {
namespace {

// Minimal rotation taking the plane with normal `from` to the plane with normal `to`, applied to v.
Vec3 rotate_between(const Vec3& v, const Vec3& from, const Vec3& to) {
  double ndot = from.dot(to);
  if (ndot <= -1.0 + 1e-12) return -v;
  Vec3 perp_old = to - ndot * from;
  Vec3 dperp = (from + to) / (1.0 + ndot);
  return v - dperp * perp_old.dot(v);
}

struct Crossing {
  uint64_t key;  // undirected edge
  Vec3 p;
  double s;
  double w;      // position on the edge: (1 - w) a + w b, a < b
  int slot;      // index of the owning segment * 2 + end
};

// Step 1, per face: the vertex directions, values and strengths after the axial flip and the
// direction-consistency rule (thesis 3.3.2); false when the face is dropped.
bool consistent_face(const std::vector<Vec3>& normals, const DirectionalFieldView& field, const std::array<int, 3>& f,
                     double cos_max, Vec3 t[3], double val[3], double str[3]) {
  const bool has_strength = field.strength != nullptr;
  for (int j = 0; j < 3; ++j) {
    t[j] = field.direction[f[j]];
    val[j] = field.value[f[j]];
    str[j] = has_strength ? field.strength[f[j]] : 0.0;
  }
  if (field.axial)
    for (int j = 1; j < 3; ++j)
      if (t[j].dot(t[0]) < 0) {
        t[j] = -t[j];
        val[j] = field.value_along(f[j], t[j]);
        if (has_strength && field.strength_along) str[j] = field.strength_along(f[j], t[j]);
      }
  double c01 = t[0].dot(t[1]), c12 = t[1].dot(t[2]), c20 = t[2].dot(t[0]);
  bool a01 = c01 >= cos_max, a12 = c12 >= cos_max, a20 = c20 >= cos_max;
  if (a01 && a12 && a20) return true;
  int odd = -1;  // the vertex re-evaluated in the mean direction of the other two
  double best = -2;
  if (a01 && c01 > best) best = c01, odd = 2;
  if (a12 && c12 > best) best = c12, odd = 0;
  if (a20 && c20 > best) best = c20, odd = 1;
  if (odd < 0) return false;
  int i1 = (odd + 1) % 3, i2 = (odd + 2) % 3;
  Vec3 mean = t[i1] + t[i2];
  Vec3 mean_n = normals[f[i1]] + normals[f[i2]];
  double ml = mean_n.norm();
  if (!(mean.norm() > 0) || !(ml > 0)) return false;
  Vec3 d = rotate_between(mean.normalized(), mean_n / ml, normals[f[odd]]);
  val[odd] = field.value_along(f[odd], d);
  if (has_strength && field.strength_along) str[odd] = field.strength_along(f[odd], d);
  return true;
}

// Step 2, per face: the crossings on its edges, placed by linear interpolation; true when there
// are exactly two and their values are finite.
bool face_crossings(const TriMesh& mesh, const std::array<int, 3>& f, const double val[3], const double str[3],
                    Crossing cr[2]) {
  int found = 0;
  for (int j = 0; j < 3; ++j) {
    int p = (j + 1) % 3, q = (j + 2) % 3;
    bool sp = val[p] >= 0, sq = val[q] >= 0;
    if (sp == sq) continue;
    if (!std::isfinite(val[p]) || !std::isfinite(val[q])) return false;
    double w = val[p] / (val[p] - val[q]);  // 0 at p, 1 at q
    uint32_t a = f[p], b = f[q];
    if (a > b) std::swap(a, b), w = 1 - w, std::swap(p, q);
    Crossing& c = cr[found < 2 ? found : 1];
    c.key = (uint64_t(a) << 32) | b;
    c.p = (1 - w) * mesh.vertices[f[p]] + w * mesh.vertices[f[q]];
    c.s = (1 - w) * str[p] + w * str[q];
    c.w = w;
    ++found;
  }
  return found == 2;
}

// Step 3: the crossings that lie on the same mesh edge become one point. A counting sort on the
// edge's lower vertex (linear time), then a small sort inside each bucket (its edges and, for a
// tie, the segment slot, which keeps the result deterministic).
void merge_crossings(const std::vector<Crossing>& all, int nv, Polylines& res) {
  std::vector<int> start(size_t(nv) + 1, 0);
  for (const auto& c : all) ++start[(c.key >> 32) + 1];
  for (int v = 0; v < nv; ++v) start[v + 1] += start[v];
  std::vector<int> order(all.size());
  {
    std::vector<int> fill(start.begin(), start.end() - 1);
    for (size_t i = 0; i < all.size(); ++i) order[fill[all[i].key >> 32]++] = static_cast<int>(i);
  }
  for (int v = 0; v < nv; ++v)
    if (start[v + 1] - start[v] > 1)
      std::sort(order.begin() + start[v], order.begin() + start[v + 1], [&all](int x, int y) {
        return all[x].key != all[y].key ? all[x].key < all[y].key : all[x].slot < all[y].slot;
      });
  res.points.reserve(all.size() / 2 + 1);
  res.strength.reserve(all.size() / 2 + 1);
  for (size_t i = 0; i < order.size();) {
    size_t j = i;
    const Crossing& first = all[order[i]];
    Vec3 p = Vec3::Zero();
    double s = 0;
    while (j < order.size() && all[order[j]].key == first.key) p += all[order[j]].p, s += all[order[j]].s, ++j;
    int id = static_cast<int>(res.points.size());
    res.points.push_back(p / double(j - i));
    res.strength.push_back(s / double(j - i));
    res.point_edge.push_back({int(first.key >> 32), int(first.key & 0xffffffffu)});
    res.point_weight.push_back(first.w);
    for (size_t k = i; k < j; ++k) res.segments[all[order[k]].slot / 2][all[order[k]].slot % 2] = id;
    i = j;
  }
}

}  // namespace

double Polylines::total_length() const {
  double L = 0;
  for (const auto& s : segments) L += (points[s[0]] - points[s[1]]).norm();
  return L;
}

std::vector<std::vector<int>> chain_segments(int n_points, const std::vector<std::array<int, 2>>& segments) {
  const int np = n_points;
  std::vector<int> deg(np, 0);
  for (const auto& s : segments) {
    ++deg[s[0]];
    ++deg[s[1]];
  }
  std::vector<int> off(np + 1, 0);
  for (int i = 0; i < np; ++i) off[i + 1] = off[i] + deg[i];
  std::vector<int> adj(off[np]), fill(off.begin(), off.end() - 1);
  for (int k = 0; k < (int)segments.size(); ++k) {
    adj[fill[segments[k][0]]++] = k;
    adj[fill[segments[k][1]]++] = k;
  }
  std::vector<char> used(segments.size(), 0);
  std::vector<std::vector<int>> out;
  auto walk = [&](int start, int seg) {
    std::vector<int> chain{start};
    int cur = start;
    while (seg >= 0 && !used[seg]) {
      used[seg] = 1;
      int nxt = segments[seg][0] == cur ? segments[seg][1] : segments[seg][0];
      chain.push_back(nxt);
      cur = nxt;
      seg = -1;
      if (deg[cur] == 2)
        for (int k = off[cur]; k < off[cur + 1]; ++k)
          if (!used[adj[k]]) seg = adj[k];
    }
    out.push_back(std::move(chain));
  };
  for (int p = 0; p < np; ++p)  // open chains start at ends and branch points
    if (deg[p] != 2)
      for (int k = off[p]; k < off[p + 1]; ++k)
        if (!used[adj[k]]) walk(p, adj[k]);
  for (int k = 0; k < (int)segments.size(); ++k)  // what is left are closed loops
    if (!used[k]) walk(segments[k][0], k);
  return out;
}

std::vector<std::vector<int>> Polylines::chains() const { return chain_segments(int(points.size()), segments); }

Polylines plane_cut(const TriMesh& mesh, const Vec3& normal, double offset) {
  const size_t n = mesh.vertices.size();
  std::vector<double> distance(n);
  for (size_t i = 0; i < n; ++i) distance[i] = mesh.vertices[i].dot(normal) - offset;
  const std::vector<Vec3> same(n, normal);  // every vertex's direction, and its normal (unused: no face is inconsistent)
  DirectionalFieldView field;
  field.direction = same.data();
  field.value = distance.data();
  field.size = n;
  field.value_along = [&distance](int v, const Vec3&) { return distance[size_t(v)]; };
  return extract_zero_crossings(mesh, same, field);
}

DirectionalFieldView view_of(const DirectionalField& f) {
  DirectionalFieldView v;
  v.direction = f.direction.data();
  v.value = f.value.data();
  v.strength = f.strength.empty() ? nullptr : f.strength.data();
  v.size = f.direction.size();
  v.axial = f.axial;
  v.value_along = f.value_along;
  v.strength_along = f.strength_along;
  return v;
}

Polylines extract_zero_crossings(const TriMesh& mesh, const std::vector<Vec3>& normals,
                                 const DirectionalField& field, const ZeroCrossingOptions& opt) {
  if (field.value.size() != field.direction.size() ||
      (!field.strength.empty() && field.strength.size() != field.direction.size()))
    throw InputError("zero-crossing extraction: per-vertex fields do not match the mesh");
  return extract_zero_crossings(mesh, normals, view_of(field), opt);
}

// The crossings; `all_strengths` (optional) receives every crossed face's segment strength.
static Polylines crossings(const TriMesh& mesh, const std::vector<Vec3>& normals, const DirectionalFieldView& field,
                           const ZeroCrossingOptions& opt, std::vector<double>* all_strengths);

Polylines extract_zero_crossings(const TriMesh& mesh, const std::vector<Vec3>& normals,
                                 const DirectionalFieldView& field, const ZeroCrossingOptions& opt) {
  return crossings(mesh, normals, field, opt, nullptr);
}

CandidateCrossings extract_candidate_crossings(const TriMesh& mesh, const std::vector<Vec3>& normals,
                                               const DirectionalFieldView& field, const ZeroCrossingOptions& opt) {
  CandidateCrossings c;
  c.lines = crossings(mesh, normals, field, opt, &c.all_strengths);
  return c;
}

static Polylines crossings(const TriMesh& mesh, const std::vector<Vec3>& normals, const DirectionalFieldView& field,
                           const ZeroCrossingOptions& opt, std::vector<double>* all_strengths) {
  const int nv = mesh.n_vertices(), nf = mesh.n_faces();
  if ((int)normals.size() != nv || (int)field.size != nv || !field.direction || !field.value || !field.value_along)
    throw InputError("zero-crossing extraction: per-vertex fields do not match the mesh");
  const double cos_max = std::cos(opt.max_angle);

  int nthreads = 1;
#ifdef _OPENMP
  nthreads = omp_get_max_threads();
#endif
  std::vector<std::vector<Crossing>> per_thread(nthreads);
  std::vector<std::vector<int>> seg_faces(nthreads);
  std::vector<std::vector<double>> strengths(all_strengths ? nthreads : 0);
  long long rejected = 0;

#pragma omp parallel reduction(+ : rejected)
  {
    int tid = 0;
#ifdef _OPENMP
    tid = omp_get_thread_num();
#endif
    auto& out = per_thread[tid];
    auto& sf = seg_faces[tid];
    out.reserve(size_t(nf) / (4 * size_t(nthreads)) + 16);  // noisy scans cross about a quarter of faces
    sf.reserve(size_t(nf) / (8 * size_t(nthreads)) + 8);
#pragma omp for schedule(static)
    for (int fi = 0; fi < nf; ++fi) {
      const auto& f = mesh.faces[fi];
      if (f[0] == f[1] || f[1] == f[2] || f[0] == f[2]) continue;
      Vec3 t[3];
      double val[3], str[3];
      if (!consistent_face(normals, field, f, cos_max, t, val, str)) {
        ++rejected;
        continue;
      }
      Crossing cr[2];
      if (!face_crossings(mesh, f, val, str, cr)) continue;
      if (opt.accept_face && !opt.accept_face(fi, val, t)) continue;
      if (all_strengths) strengths[tid].push_back(0.5 * (cr[0].s + cr[1].s));
      if (0.5 * (cr[0].s + cr[1].s) < opt.min_strength) continue;
      int seg = static_cast<int>(sf.size());
      cr[0].slot = seg * 2;
      cr[1].slot = seg * 2 + 1;
      out.push_back(cr[0]);
      out.push_back(cr[1]);
      sf.push_back(fi);
    }
  }

  if (all_strengths) {
    all_strengths->clear();
    for (const auto& v : strengths) all_strengths->insert(all_strengths->end(), v.begin(), v.end());
  }
  // Concatenate per-thread results (deterministic order) and merge points on shared edges.
  Polylines res;
  res.rejected_faces = rejected;
  std::vector<Crossing> all;
  size_t total = 0;
  for (auto& v : per_thread) total += v.size();
  all.reserve(total);
  int seg_base = 0;
  for (int t = 0; t < nthreads; ++t) {
    for (auto c : per_thread[t]) {
      c.slot += 2 * seg_base;
      all.push_back(c);
    }
    res.segment_face.insert(res.segment_face.end(), seg_faces[t].begin(), seg_faces[t].end());
    seg_base += static_cast<int>(seg_faces[t].size());
  }
  res.segments.assign(seg_base, {0, 0});
  merge_crossings(all, nv, res);
  return res;
}

Vec3 face_gradient(const TriMesh& mesh, int face, const double val[3]) {
  const auto& fv = mesh.faces[face];
  const Vec3 &p0 = mesh.vertices[fv[0]], &p1 = mesh.vertices[fv[1]], &p2 = mesh.vertices[fv[2]];
  const Vec3 n = (p1 - p0).cross(p2 - p0);
  const double a2 = n.squaredNorm();
  if (!(a2 > 0)) return Vec3::Zero();
  // grad = sum_i val_i (n x e_i) / |n|^2, e_i the edge opposite vertex i (counter-clockwise).
  return (val[0] * n.cross(p2 - p1) + val[1] * n.cross(p0 - p2) + val[2] * n.cross(p1 - p0)) / a2;
}

std::vector<double> interpolate_at_points(const Polylines& c, const std::vector<double>& f) {
  std::vector<double> out(c.points.size(), 0.0);
  for (size_t i = 0; i < c.points.size() && i < c.point_edge.size(); ++i)
    out[i] = (1 - c.point_weight[i]) * f[c.point_edge[i][0]] + c.point_weight[i] * f[c.point_edge[i][1]];
  return out;
}

}  // namespace reliefkit
