#include "reliefkit/base/scale.h"
#include "reliefkit/base/disjoint_sets.h"
#include "reliefkit/base/memory.h"
#include "reliefkit/base/work_counts.h"

#include <Eigen/Dense>
#include <algorithm>
#include <limits>
#include <cctype>
#include <cstdint>
#include <cstdlib>
#include <cmath>
#include <numeric>
#include <parallel/algorithm>
#include <sstream>

namespace reliefkit {
namespace {

// The median residual deviation underestimates the noise by 1.5-3 % over 2.5-20 % noise on the
// synthetic surfaces of bench/bench_noise (the fit absorbs a little of it).
constexpr double kNoiseCalibration = 1.02;

std::string number(double x) {
  std::ostringstream s;
  s << x;
  return s.str();
}

}  // namespace

namespace {

// Connected parts (faces sharing a vertex): each vertex's root (its part's lowest vertex), and
// each face's (-1: a face with a missing vertex).
struct Parts {
  std::vector<int> vertex_root, face_root;
  std::vector<long long> faces_of;  // by root
};

Parts connected_parts(const TriMesh& mesh) {
  const int nv = mesh.n_vertices();
  const long long nf = static_cast<long long>(mesh.faces.size());
  auto valid = [nv](const std::array<int, 3>& f) {
    return f[0] >= 0 && f[1] >= 0 && f[2] >= 0 && f[0] < nv && f[1] < nv && f[2] < nv;
  };
  DisjointSets sets(nv);
#pragma omp parallel for schedule(dynamic, 4096)
  for (long long i = 0; i < nf; ++i) {
    const auto& f = mesh.faces[size_t(i)];
    if (valid(f)) sets.unite(f[0], f[1]), sets.unite(f[0], f[2]);
  }
  Parts p;
  sized(p.vertex_root, size_t(nv));
#pragma omp parallel for schedule(static)
  for (int v = 0; v < nv; ++v) p.vertex_root[size_t(v)] = sets.find(v);
  sized(p.face_root, size_t(nf), -1);
#pragma omp parallel for schedule(static)
  for (long long i = 0; i < nf; ++i) {
    const auto& f = mesh.faces[size_t(i)];
    if (f[0] >= 0 && f[0] < nv) p.face_root[size_t(i)] = p.vertex_root[size_t(f[0])];
  }
  p.faces_of.assign(size_t(nv), 0);
  for (int r : p.face_root)
    if (r >= 0) ++p.faces_of[size_t(r)];
  return p;
}

// The main part's edge lengths (each face's three; non-finite ones left out), their sum and the
// part's bounding box, computed on every core in blocks of faces.
struct EdgeLengths {
  std::vector<float> length;
  double sum = 0;
  Eigen::AlignedBox3d box;
};

EdgeLengths main_part_edges(const TriMesh& mesh, const std::vector<int>& face_root, int main_root) {
  constexpr long long kBlock = 1 << 16;
  const long long nf = static_cast<long long>(mesh.faces.size());
  const long long blocks = (nf + kBlock - 1) / kBlock;
  EdgeLengths e;
  sized(e.length, size_t(nf) * 3, std::numeric_limits<float>::quiet_NaN());
  std::vector<double> block_sum(size_t(blocks), 0.0);
  std::vector<Eigen::AlignedBox3d> block_box(static_cast<size_t>(blocks));
#pragma omp parallel for schedule(static)
  for (long long b = 0; b < blocks; ++b) {
    for (long long i = b * kBlock; i < std::min(nf, (b + 1) * kBlock); ++i) {
      if (face_root[size_t(i)] != main_root) continue;
      const auto& f = mesh.faces[size_t(i)];
      for (int j = 0; j < 3; ++j) {
        const Vec3& p = mesh.vertices[f[j]];
        if (p.allFinite()) block_box[size_t(b)].extend(p);
        const double l = (p - mesh.vertices[f[(j + 1) % 3]]).norm();
        if (!std::isfinite(l)) continue;
        e.length[size_t(3 * i + j)] = float(l);
        block_sum[size_t(b)] += l;
      }
    }
  }
  for (long long b = 0; b < blocks; ++b) e.sum += block_sum[size_t(b)], e.box.extend(block_box[size_t(b)]);
  e.length.erase(std::remove_if(e.length.begin(), e.length.end(), [](float l) { return std::isnan(l); }),
                 e.length.end());
  return e;
}

// A quarter of the mean squared length over the edges at most 4 x `edge` long (and not zero): the
// variance one explicit diffusion step spreads by (it matches a Gaussian to 0.8 % on a grid).
double diffusion_step_variance(const std::vector<float>& length, double edge) {
  const double cap = 16 * edge * edge;
  double sum = 0;
  long long n = 0;
#pragma omp parallel for schedule(static) reduction(+ : sum, n)
  for (long long i = 0; i < static_cast<long long>(length.size()); ++i) {
    const double x = double(length[size_t(i)]) * double(length[size_t(i)]);
    if (x > 0 && x <= cap) sum += x, ++n;
  }
  return n > 0 ? 0.25 * sum / double(n) : 0.0;
}

}  // namespace

MeshScale mesh_scale(const TriMesh& mesh) {
  count_work(Work::MeshScale);
  MeshScale s;
  const int nv = mesh.n_vertices();
  const Parts parts = connected_parts(mesh);
  int main_root = -1;
  for (int v = 0; v < nv; ++v)
    if (parts.faces_of[size_t(v)] > 0) {
      ++s.parts;
      if (main_root < 0 || parts.faces_of[size_t(v)] > parts.faces_of[size_t(main_root)]) main_root = v;
    }
  if (main_root < 0) return s;
  s.main_faces = parts.faces_of[size_t(main_root)];
  const double min_faces = kMainPartShare * double(s.main_faces);
  s.counts.assign(size_t(nv), 0);
  for (int v = 0; v < nv; ++v) s.counts[size_t(v)] = double(parts.faces_of[size_t(parts.vertex_root[size_t(v)])]) >= min_faces;
  for (int r : parts.face_root)
    if (r >= 0 && r != main_root && double(parts.faces_of[size_t(r)]) < min_faces) ++s.debris_faces;
  EdgeLengths e = main_part_edges(mesh, parts.face_root, main_root);
  if (e.length.empty()) return s;
  s.mean_edge = e.sum / double(e.length.size());
  auto mid = e.length.begin() + e.length.size() / 2;
  __gnu_parallel::nth_element(e.length.begin(), mid, e.length.end());
  s.edge = *mid;
  if (!(s.edge > 0)) s.edge = s.mean_edge;  // more than half the edges of zero length
  s.object_size = e.box.isEmpty() ? 0 : e.box.diagonal().norm();
  s.step_variance = diffusion_step_variance(e.length, s.edge);
  return s;
}

std::vector<double> counted_values(const std::vector<double>& per_vertex, const std::vector<char>& counts) {
  if (counts.size() != per_vertex.size()) return per_vertex;
  std::vector<double> out;
  out.reserve(per_vertex.size());
  for (size_t i = 0; i < per_vertex.size(); ++i)
    if (counts[i]) out.push_back(per_vertex[i]);
  return out;
}

void require_range(double value, const std::string& name, double lo, double hi) {
  if (std::isfinite(value) && value >= lo && value <= hi) return;
  throw InputError(name + " must be between " + number(lo) + " and " + number(hi) + " (got " + number(value) + ").");
}

Length parse_length(const std::string& text, const std::string& name, double min_edges, double max_edges) {
  std::string t;
  for (char ch : text)
    if (!std::isspace(static_cast<unsigned char>(ch))) t += char(std::tolower(static_cast<unsigned char>(ch)));
  if (t.empty() || t == "auto" || t == "automatic") return Length::automatic();
  const std::string range = "\"auto\" or a number of edge lengths between " + number(min_edges) + " and " +
                            number(max_edges);
  size_t used = 0;
  double x = 0;
  try {
    x = std::stod(t, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used != t.size()) throw InputError(name + " must be " + range + " (got \"" + text + "\").");
  if (!(std::isfinite(x) && x >= min_edges && x <= max_edges))
    throw InputError(name + " must be " + range + " (got " + number(x) + ").");
  return Length::in_edges(x);
}

void Length::check(const std::string& name, double lo, double hi, double edge) const {
  if (kind == Kind::Edges) return require_range(value, name + " (edge lengths)", lo, hi);
  if (kind != Kind::Units) return;
  if (!(std::isfinite(value) && value >= 0))
    throw InputError(name + " must be a finite, non-negative length (got " + number(value) + ").");
  if (edge > 0 && !(value / edge >= lo && value / edge <= hi))
    throw InputError(name + " is " + number(value) + " mesh units = " + number(value / edge) +
                     " edge lengths of this mesh; it must be between " + number(lo) + " and " + number(hi) +
                     " edge lengths. Give it as \"auto\" or a number of edge lengths.");
}

std::string format_length(const Length& length) {
  return length.is_auto() ? "auto" : length.kind == Length::Kind::Edges ? number(length.value) : number(length.value) + " mesh units";
}

NoiseEstimate estimate_noise(const TriMesh& mesh, const MeshScale& scale, int max_samples, const VertexFaces* faces) {
  count_work(Work::Noise);
  NoiseEstimate out;
  const int nv = mesh.n_vertices();
  if (nv == 0 || !(scale.edge > 0)) return out;
  const VertexFaces own = faces ? VertexFaces() : vertex_faces(mesh);
  const VertexFaces& vf = faces ? *faces : own;
  std::vector<int> candidates;
  candidates.reserve(nv);
  for (int v = 0; v < nv; ++v)
    if ((scale.counts.empty() || scale.counts[v]) && vf.offset[v + 1] > vf.offset[v]) candidates.push_back(v);
  if (candidates.empty()) return out;
  const size_t stride = std::max<size_t>(1, candidates.size() / size_t(std::max(1, max_samples)));
  std::vector<int> sample;
  for (size_t i = 0; i < candidates.size(); i += stride) sample.push_back(candidates[i]);
  const int ns = static_cast<int>(sample.size());
  std::vector<double> sd(ns, -1);
  std::vector<std::vector<int>> marks = per_thread(size_t(nv), -1);
#pragma omp parallel
  {
    std::vector<int> ring, &mark = marks[size_t(omp_get_thread_num())];
#pragma omp for schedule(dynamic, 1024)
    for (int i = 0; i < ns; ++i) {
      const int v = sample[i];
      // Two-ring of v and the area-weighted normal of its one-ring.
      ring.clear();
      Vec3 n(0, 0, 0);
      mark[v] = v;
      for (int k = vf.offset[v]; k < vf.offset[v + 1]; ++k) {
        const auto& f = mesh.faces[vf.face[k]];
        n += (mesh.vertices[f[1]] - mesh.vertices[f[0]]).cross(mesh.vertices[f[2]] - mesh.vertices[f[0]]);
        for (int j = 0; j < 3; ++j)
          if (mark[f[j]] != v && ring.size() < 64) mark[f[j]] = v, ring.push_back(f[j]);
      }
      const size_t first = ring.size();
      for (size_t r = 0; r < first && ring.size() < 64; ++r)  // bounded: high-valence neighbours
        for (int k = vf.offset[ring[r]]; k < vf.offset[ring[r] + 1] && ring.size() < 64; ++k)
          for (int u : mesh.faces[vf.face[k]])
            if (mark[u] != v) mark[u] = v, ring.push_back(u);
      const int m = static_cast<int>(ring.size()) + 1;
      if (m < 10 || !(n.norm() > 0)) continue;
      n.normalize();
      Vec3 a = std::abs(n.x()) < 0.9 ? Vec3(1, 0, 0) : Vec3(0, 1, 0);
      Vec3 t1 = n.cross(a).normalized(), t2 = n.cross(t1);
      Eigen::Matrix<double, 6, 6> A = Eigen::Matrix<double, 6, 6>::Zero();
      Eigen::Matrix<double, 6, 1> b = Eigen::Matrix<double, 6, 1>::Zero();
      double zz = 0;
      const Vec3& p0 = mesh.vertices[v];
      const double inv = 1 / scale.edge;
      for (int r = -1; r < static_cast<int>(ring.size()); ++r) {
        Vec3 d = ((r < 0 ? p0 : mesh.vertices[ring[r]]) - p0) * inv;
        double x = d.dot(t1), y = d.dot(t2), z = d.dot(n);
        Eigen::Matrix<double, 6, 1> phi;
        phi << 1, x, y, x * x, x * y, y * y;
        A.noalias() += phi * phi.transpose();
        b += z * phi;
        zz += z * z;
      }
      Eigen::LDLT<Eigen::Matrix<double, 6, 6>> ldlt(A);
      if (ldlt.info() != Eigen::Success) continue;
      Eigen::Matrix<double, 6, 1> c = ldlt.solve(b);
      if (!c.allFinite()) continue;
      const double rss = std::max(0.0, zz - c.dot(b));
      sd[i] = std::sqrt(rss / double(m - 6)) * scale.edge;
    }
  }
  std::vector<double> ok;
  for (double x : sd)
    if (x >= 0 && std::isfinite(x)) ok.push_back(x);
  if (ok.empty()) return out;
  auto mid = ok.begin() + ok.size() / 2;
  std::nth_element(ok.begin(), mid, ok.end());
  out.sigma = kNoiseCalibration * *mid;
  out.relative = out.sigma / scale.edge;
  out.samples = static_cast<long long>(ok.size());
  return out;
}

}  // namespace reliefkit

namespace reliefkit {

double automatic_presmoothing(const NoiseEstimate& noise, const MeshScale& scale) {
  // Noise of standard deviation sigma on a mesh of edge h, smoothed with a Gaussian of scale s,
  // leaves curvature derivatives of about sigma h / s^4: the pre-smoothing that keeps that at
  // a fixed fraction of what an object of size D gives is s = c (sigma h D^2)^(1/4) — the same
  // curves at any resolution (h) and in any unit. c = 0.24 is measured on the noisy cylinder
  // relief at 100 K and 1 M faces (bench/bench_noise --sweep; docs/parameters.md). The noise a
  // clean mesh shows (below kCleanNoise edge lengths, mostly its own fine detail) is not smoothed.
  const double excess = noise.sigma - kCleanNoise * scale.edge;
  if (!(excess > 0) || !(scale.edge > 0) || !(scale.object_size > 0)) return 0;
  constexpr double c = 0.24;
  const double s = c * std::pow(excess * scale.edge * scale.object_size * scale.object_size, 0.25);
  return std::min(s, 20 * scale.edge);
}

}  // namespace reliefkit

namespace reliefkit {

TriMesh noise_patch(double relative_noise, int n) {
  count_work(Work::NoiseFloor);
  TriMesh m;
  uint64_t state = 0x2545F4914F6CDD1Dull;
  auto uniform = [&] {
    state ^= state >> 12, state ^= state << 25, state ^= state >> 27;
    return double((state * 0x2545F4914F6CDD1Dull) >> 11) * (1.0 / 9007199254740992.0);
  };
  auto normal = [&] {
    double u = std::max(uniform(), 1e-300), v = uniform();
    return std::sqrt(-2 * std::log(u)) * std::cos(6.283185307179586 * v);
  };
  const double cell = 1 / 1.2;  // a jittered grid's median edge (sides and diagonals) is about 1.2 cells
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      const bool inner = i > 0 && j > 0 && i < n && j < n;
      double x = i + (inner ? 0.6 * (uniform() - 0.5) : 0), y = j + (inner ? 0.6 * (uniform() - 0.5) : 0);
      m.vertices.emplace_back(x * cell, y * cell, relative_noise * normal());
    }
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      int a = j * (n + 1) + i, b = a + 1, c = a + n + 1, d = c + 1;
      m.faces.push_back({a, b, d});
      m.faces.push_back({a, d, c});
    }
  return m;
}

int noise_patch_cells(long long faces) {
  return static_cast<int>(std::clamp(std::sqrt(double(faces) / 2), 30.0, 100.0));
}

double percentile(std::vector<double> values, double q) {
  if (values.empty()) return 0;
  auto k = values.begin() + static_cast<long>(std::clamp(q, 0.0, 1.0) * double(values.size() - 1));
  std::nth_element(values.begin(), k, values.end());
  return *k;
}

double weighted_median(std::vector<std::pair<double, double>> value_weight) {
  std::sort(value_weight.begin(), value_weight.end());
  double total = 0;
  for (const auto& vw : value_weight) total += vw.second;
  double run = 0;
  for (const auto& vw : value_weight)
    if ((run += vw.second) >= total / 2) return vw.first;
  return value_weight.empty() ? 0 : value_weight.back().first;
}

}  // namespace reliefkit

namespace reliefkit {

int noise_patch_margin(double presmoothing_edges) { return 3 + static_cast<int>(std::ceil(2 * presmoothing_edges)); }

bool inside_noise_patch(int v, int n, int margin) {
  const int i = v % (n + 1), j = v / (n + 1);
  return i >= margin && j >= margin && i <= n - margin && j <= n - margin;
}

std::vector<char> interior_segments(const Polylines& curves, int n, int margin) {
  std::vector<char> inside(curves.segments.size());
  for (size_t k = 0; k < curves.segments.size(); ++k) {
    const int cell = curves.segment_face[k] / 2, i = cell % n, j = cell / n;
    inside[k] = i >= margin && j >= margin && i < n - margin && j < n - margin;
  }
  return inside;
}

std::vector<double> interior_segment_strengths(const Polylines& curves, int n, int margin) {
  const std::vector<char> inside = interior_segments(curves, n, margin);
  std::vector<double> out;
  for (size_t k = 0; k < curves.segments.size(); ++k)
    if (inside[k]) out.push_back(0.5 * (curves.strength[curves.segments[k][0]] + curves.strength[curves.segments[k][1]]));
  return out;
}

}  // namespace reliefkit
