#include "reliefkit/base/curvature.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

#include "reliefkit/base/memory.h"
#include "reliefkit/base/smoothing.h"
#include "reliefkit/base/work_counts.h"

namespace reliefkit {
namespace {

inline int next3(int i) { return i == 2 ? 0 : i + 1; }
inline int prev3(int i) { return i == 0 ? 2 : i - 1; }

// Rotates the frame (u, v) about u x v so that its normal becomes `n` (minimal rotation).
inline void rotate_frame(Vec3& u, Vec3& v, const Vec3& n) {
  Vec3 old_n = u.cross(v);
  double ndot = old_n.dot(n);
  if (ndot <= -1.0) {
    u = -u;
    v = -v;
    return;
  }
  Vec3 perp_old = n - ndot * old_n;
  Vec3 dperp = (old_n + n) / (1.0 + ndot);
  u -= dperp * perp_old.dot(u);
  v -= dperp * perp_old.dot(v);
}

// II given as (ku, kuv, kv) in frame (ou, ov), re-expressed in frame (nu, nv).
inline void project_II(const Vec3& ou, const Vec3& ov, double ku, double kuv, double kv, Vec3 nu,
                       Vec3 nv, double& out_ku, double& out_kuv, double& out_kv) {
  rotate_frame(nu, nv, ou.cross(ov));
  double u1 = nu.dot(ou), v1 = nu.dot(ov), u2 = nv.dot(ou), v2 = nv.dot(ov);
  out_ku = ku * u1 * u1 + kuv * (2 * u1 * v1) + kv * v1 * v1;
  out_kuv = ku * u1 * u2 + kuv * (u1 * v2 + u2 * v1) + kv * v1 * v2;
  out_kv = ku * u2 * u2 + kuv * (2 * u2 * v2) + kv * v2 * v2;
}

// Derivative tensor (a, b, c, d) in frame (ou, ov) re-expressed in frame (nu, nv).
inline CurvatureDerivative project_C(const Vec3& ou, const Vec3& ov, const double o[4], Vec3 nu,
                                     Vec3 nv) {
  rotate_frame(nu, nv, ou.cross(ov));
  double u1 = nu.dot(ou), v1 = nu.dot(ov), u2 = nv.dot(ou), v2 = nv.dot(ov);
  CurvatureDerivative r;
  r.a = o[0] * u1 * u1 * u1 + o[1] * 3 * u1 * u1 * v1 + o[2] * 3 * u1 * v1 * v1 + o[3] * v1 * v1 * v1;
  r.b = o[0] * u1 * u1 * u2 + o[1] * (u1 * u1 * v2 + 2 * u2 * u1 * v1) +
        o[2] * (u2 * v1 * v1 + 2 * u1 * v1 * v2) + o[3] * v1 * v1 * v2;
  r.c = o[0] * u1 * u2 * u2 + o[1] * (u2 * u2 * v1 + 2 * u1 * u2 * v2) +
        o[2] * (u1 * v2 * v2 + 2 * u2 * v2 * v1) + o[3] * v1 * v2 * v2;
  r.d = o[0] * u2 * u2 * u2 + o[1] * 3 * u2 * u2 * v2 + o[2] * 3 * u2 * v2 * v2 + o[3] * v2 * v2 * v2;
  return r;
}

// Mixed Voronoi corner areas of a triangle with edges e[j] opposite corner j (Meyer et al. 2003).
inline void mixed_corner_areas(const Vec3 e[3], double area, double c[3]) {
  double l2[3] = {e[0].squaredNorm(), e[1].squaredNorm(), e[2].squaredNorm()};
  double ew[3] = {l2[0] * (l2[1] + l2[2] - l2[0]), l2[1] * (l2[2] + l2[0] - l2[1]),
                  l2[2] * (l2[0] + l2[1] - l2[2])};
  if (ew[0] <= 0) {  // obtuse at corner 0
    c[1] = -0.25 * l2[2] * area / e[0].dot(e[2]);
    c[2] = -0.25 * l2[1] * area / e[0].dot(e[1]);
    c[0] = area - c[1] - c[2];
  } else if (ew[1] <= 0) {
    c[2] = -0.25 * l2[0] * area / e[1].dot(e[0]);
    c[0] = -0.25 * l2[2] * area / e[1].dot(e[2]);
    c[1] = area - c[2] - c[0];
  } else if (ew[2] <= 0) {
    c[0] = -0.25 * l2[1] * area / e[2].dot(e[1]);
    c[1] = -0.25 * l2[0] * area / e[2].dot(e[0]);
    c[2] = area - c[0] - c[1];
  } else {
    double s = 0.5 * area / (ew[0] + ew[1] + ew[2]);
    for (int j = 0; j < 3; ++j) c[j] = s * (ew[next3(j)] + ew[prev3(j)]);
  }
  for (int j = 0; j < 3; ++j)
    if (!std::isfinite(c[j])) c[j] = 0;
}

long long count_degenerate_faces(const TriMesh& mesh) {
  long long n = 0;
  const int nf = mesh.n_faces();
#pragma omp parallel for schedule(static) reduction(+ : n)
  for (int i = 0; i < nf; ++i) {
    const auto& f = mesh.faces[i];
    double a = (mesh.vertices[f[1]] - mesh.vertices[f[0]]).cross(mesh.vertices[f[2]] - mesh.vertices[f[0]]).norm();
    if (!(a > 0) || !std::isfinite(a)) ++n;
  }
  return n;
}

// Per-face data kept between the passes (floats: 64 bytes a face).
struct FaceFrame {
  float t[3], b[3];   // orthonormal tangent frame of the face
  float area[3];      // corner areas
  float II[3];        // fitted second fundamental form (ku, kuv, kv) in (t, b)
  float C[4];         // fitted derivative tensor in (t, b)
};

inline Vec3 v3(const float* p) { return Vec3(p[0], p[1], p[2]); }
inline void put(float* p, const Vec3& v) {
  p[0] = float(v.x()); p[1] = float(v.y()); p[2] = float(v.z());
}

void report(Progress cb, int pct, const char* what) {
  if (cb) cb(pct, what);
}

}  // namespace

std::vector<Vec3> vertex_normals(const TriMesh& mesh, const VertexFaces& vf) {
  const int nv = mesh.n_vertices();
  std::vector<Vec3> n;
  sized(n, nv, Vec3(Vec3::Zero()));
#pragma omp parallel for schedule(static)
  for (int v = 0; v < nv; ++v) {
    Vec3 acc = Vec3::Zero();
    for (int k = vf.offset[v]; k < vf.offset[v + 1]; ++k) {
      const auto& f = mesh.faces[vf.face[k]];
      int c = vf.corner[k];
      const Vec3& p = mesh.vertices[f[c]];
      Vec3 e1 = mesh.vertices[f[next3(c)]] - p, e2 = mesh.vertices[f[prev3(c)]] - p;
      double w = e1.squaredNorm() * e2.squaredNorm();
      Vec3 fn = e1.cross(e2);
      if (w > 0 && std::isfinite(w)) acc += fn / w;  // Max 1999: sin(angle) / (|e1| |e2|)
    }
    double len = acc.norm();
    n[v] = (len > 0 && std::isfinite(len)) ? Vec3(acc / len) : Vec3(0, 0, 1);
  }
  return n;
}

std::vector<std::array<double, 3>> corner_areas(const TriMesh& mesh) {
  const int nf = mesh.n_faces();
  std::vector<std::array<double, 3>> ca;
  sized(ca, nf);
#pragma omp parallel for schedule(static)
  for (int i = 0; i < nf; ++i) {
    const auto& f = mesh.faces[i];
    Vec3 e[3] = {mesh.vertices[f[2]] - mesh.vertices[f[1]], mesh.vertices[f[0]] - mesh.vertices[f[2]],
                 mesh.vertices[f[1]] - mesh.vertices[f[0]]};
    double area = 0.5 * e[0].cross(e[1]).norm();
    double c[3] = {0, 0, 0};
    if (area > 0 && std::isfinite(area)) mixed_corner_areas(e, area, c);
    ca[i] = {c[0], c[1], c[2]};
  }
  return ca;
}

double Curvature::normal_curvature(int v, const Vec3& t) const {
  double u1 = t.dot(dir1[v]), u2 = t.dot(dir2[v]);
  double n2 = u1 * u1 + u2 * u2;
  if (!(n2 > 0)) return 0;
  return (k1[v] * u1 * u1 + k2[v] * u2 * u2) / n2;
}

double Curvature::derivative_along(int v, const Vec3& t) const {
  double u1 = t.dot(dir1[v]), u2 = t.dot(dir2[v]);
  double n = std::sqrt(u1 * u1 + u2 * u2);
  if (!(n > 0) || dcurv.empty()) return 0;
  return dcurv[v].along(u1 / n, u2 / n);
}

namespace {

// Diagonalises the symmetric II = [[ku, kuv], [kuv, kv]] given in the tangent frame (u, w) of
// normal n; writes k1 >= k2 and their directions.
inline void diagonalize(const Vec3& u, const Vec3& w, const Vec3& n, double ku, double kuv, double kv, double& k1,
                        double& k2, Vec3& d1, Vec3& d2) {
  double c = 1, s = 0, tt = 0;
  if (kuv != 0) {
    double h = 0.5 * (kv - ku) / kuv;
    tt = (h < 0) ? 1 / (h - std::sqrt(1 + h * h)) : 1 / (h + std::sqrt(1 + h * h));
    c = 1 / std::sqrt(1 + tt * tt);
    s = tt * c;
  }
  double ka = ku - tt * kuv, kb = kv + tt * kuv;
  if (ka >= kb) {
    k1 = ka;
    k2 = kb;
    d1 = c * u - s * w;
  } else {
    k1 = kb;
    k2 = ka;
    d1 = s * u + c * w;
  }
  d2 = n.cross(d1);
}

inline Vec3 any_tangent(const Vec3& n) {
  Vec3 u = std::abs(n.x()) < 0.9 ? Vec3(1, 0, 0) : Vec3(0, 1, 0);
  return (u - n * n.dot(u)).normalized();
}

constexpr int kMaxNeighbours = 128;

// Collects the two-ring of v (without v), one-ring first, from the vertex-face adjacency.
// `mark` holds one stamp per vertex (per thread); stamping with v + 1 makes a reset unnecessary.
// Returns whether v lies on the mesh's border: its fan is open (more neighbours than faces).
inline bool two_ring(const TriMesh& mesh, const VertexFaces& vf, int v, std::vector<int>& out,
                     std::vector<int>& mark) {
  out.clear();
  const int stamp = v + 1;
  mark[v] = stamp;
  // At most kMaxNeighbours are collected (the fit uses no more): around a vertex of very high
  // valence (the pole of a fan or a UV sphere) every neighbour's two-ring would otherwise walk all
  // of the pole's faces, and the cost would grow with the square of the valence.
  auto add_ring_of = [&](int c) {
    for (int k = vf.offset[c]; k < vf.offset[c + 1] && out.size() < size_t(kMaxNeighbours); ++k) {
      const auto& f = mesh.faces[vf.face[k]];
      for (int j = 0; j < 3; ++j)
        if (mark[f[j]] != stamp) mark[f[j]] = stamp, out.push_back(f[j]);
    }
  };
  add_ring_of(v);
  const size_t first = out.size();
  for (size_t i = 0; i < first && out.size() < size_t(kMaxNeighbours); ++i) add_ring_of(out[i]);
  return first > size_t(vf.offset[v + 1] - vf.offset[v]);
}

// Exponents (i, j) and factors c of the basis X^i Y^j * c:
// [X, Y, X^2/2, XY, Y^2/2, X^3/6, X^2 Y/2, X Y^2/2, Y^3/6].
constexpr int kBasisI[9] = {1, 0, 2, 1, 0, 3, 2, 1, 0};
constexpr int kBasisJ[9] = {0, 1, 0, 1, 2, 0, 1, 2, 3};
constexpr double kBasisC[9] = {1, 1, 0.5, 1, 0.5, 1.0 / 6, 0.5, 0.5, 1.0 / 6};

// Moments S[i][j] = sum X^i Y^j (i + j <= 6; row i, columns 0..7) and T[i][j] = sum Z X^i Y^j
// (i + j <= 3) of the neighbours in the frame (u, w, n). Each row of S is accumulated as two
// 4-wide vectors (X^i times the powers of Y), so the loop over neighbours keeps every sum in
// registers; AVX2 where the processor has it (function multi-versioning).
typedef double double4 __attribute__((vector_size(32)));

__attribute__((target_clones("avx2", "default"))) void height_moments(const double* dx, const double* dy,
                                                                     const double* dz, int m, const double* frame,
                                                                     double S[7][8], double T[4][4]) {
  double4 s[7][2], t[4];
  for (int i = 0; i < 7; ++i) s[i][0] = s[i][1] = double4{0, 0, 0, 0};
  for (int i = 0; i < 4; ++i) t[i] = double4{0, 0, 0, 0};
  for (int k = 0; k < m; ++k) {
    const double X = dx[k] * frame[0] + dy[k] * frame[1] + dz[k] * frame[2];
    const double Y = dx[k] * frame[3] + dy[k] * frame[4] + dz[k] * frame[5];
    const double Z = dx[k] * frame[6] + dy[k] * frame[7] + dz[k] * frame[8];
    const double Y2 = Y * Y, Y3 = Y2 * Y, Y4 = Y2 * Y2;
    const double4 y0 = {1, Y, Y2, Y3}, y1 = {Y4, Y4 * Y, Y3 * Y3, 0};
    double xi = 1;
    for (int i = 0; i < 7; ++i) {
      s[i][0] += xi * y0;
      s[i][1] += xi * y1;
      if (i < 4) t[i] += (Z * xi) * y0;
      xi *= X;
    }
  }
  for (int i = 0; i < 7; ++i)
    for (int j = 0; j < 4; ++j) S[i][j] = s[i][0][j], S[i][4 + j] = s[i][1][j];
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) T[i][j] = t[i][j];
}

// Least-squares fit of z = sum_k x_k * basis_k over the neighbours with the first N basis
// functions (N = 9: cubic, N = 5: quadratic), from the moments, by an LDL^T factorisation of
// the normal equations written out for fixed N (no square roots; Eigen's general solvers cost
// more than the whole fit at this size). False if the system is singular.
template <int N>
bool solve_height(const double S[7][8], const double T[4][4], double* x) {
  double L[N][N], inv[N], b[N], y[N];
  for (int p = 0; p < N; ++p) {
    for (int q = 0; q <= p; ++q)
      L[p][q] = kBasisC[p] * kBasisC[q] * S[kBasisI[p] + kBasisI[q]][kBasisJ[p] + kBasisJ[q]];
    b[p] = kBasisC[p] * T[kBasisI[p]][kBasisJ[p]];
  }
  const double tiny = 1e-14 * (L[0][0] + L[1][1]);
  for (int j = 0; j < N; ++j) {  // below the diagonal L[i][j] holds l_ij * d_j
    double d = L[j][j];
    for (int k = 0; k < j; ++k) d -= L[j][k] * L[j][k] * inv[k];
    if (!(d > tiny)) return false;
    inv[j] = 1 / d;
    for (int i = j + 1; i < N; ++i) {
      double sum = L[i][j];
      for (int k = 0; k < j; ++k) sum -= L[i][k] * L[j][k] * inv[k];
      L[i][j] = sum;
    }
  }
  for (int i = 0; i < N; ++i) {
    double sum = b[i];
    for (int k = 0; k < i; ++k) sum -= L[i][k] * inv[k] * y[k];
    y[i] = sum;
  }
  for (int i = N - 1; i >= 0; --i) {
    double sum = y[i] * inv[i];
    for (int k = i + 1; k < N; ++k) sum -= L[k][i] * inv[i] * x[k];
    x[i] = sum;
  }
  for (int k = 0; k < N; ++k)
    if (!std::isfinite(x[k])) return false;
  return true;
}

// Least-squares osculating jet at one vertex: the height over the tangent plane of the vertex
// normal n0 (Max's weights),
//   z = g1 x + g2 y + (A x^2 + 2B xy + C y^2)/2 + (D x^3 + 3E x^2 y + 3F x y^2 + G y^3)/6,
// fitted to the two-ring (cubic with >= 12 neighbours, quadratic with >= 6; on the border the
// normal and II from the quadratic: a one-sided cubic swung the normal by tens of degrees on a
// noisy plane's rim, the quadratic by about one). The fitted gradient
// (g1, g2) corrects the normal: n = normalise(n0 - g1 u - g2 w), and II is re-expressed in the
// corrected tangent plane with the metric factor 1/sqrt(1 + |g|^2), so an inexact starting
// normal costs only second-order terms. Returns false if no fit was possible.
bool jet_at(const TriMesh& mesh, int v, const std::vector<int>& nb, bool on_border, std::vector<double>& buf, Vec3& n,
            double& ku, double& kuv, double& kv, Vec3& u, Vec3& w, double C[4]) {
  const int m = std::min(static_cast<int>(nb.size()), kMaxNeighbours);  // one-ring comes first
  if (m < 6) return false;
  buf.resize(3 * size_t(m));
  double *dx = buf.data(), *dy = dx + m, *dz = dy + m;
  const Vec3& p = mesh.vertices[v];
  double s2 = 0;
  for (int j = 0; j < m; ++j) {
    Vec3 d = mesh.vertices[nb[j]] - p;
    dx[j] = d.x(), dy[j] = d.y(), dz[j] = d.z();
    s2 += d.squaredNorm();
  }
  double s = std::sqrt(s2 / m);
  if (!(s > 0) || !std::isfinite(s)) return false;
  const double inv = 1 / s;
  for (int j = 0; j < 3 * m; ++j) buf[j] *= inv;  // dx, dy, dz
  double x[9] = {0, 0, 0, 0, 0, 0, 0, 0, 0};
  Vec3 u0 = any_tangent(n), w0 = n.cross(u0);
  const double frame[9] = {u0.x(), u0.y(), u0.z(), w0.x(), w0.y(), w0.z(), n.x(), n.y(), n.z()};
  double S[7][8], T[4][4];
  height_moments(dx, dy, dz, m, frame, S, T);
  // On the border the third-order terms still come from the cubic (its one-sided C keeps the
  // derivative's sign), the normal and II from the quadratic.
  const bool cubic = m >= 12;
  if (!(cubic ? solve_height<9>(S, T, x) : solve_height<5>(S, T, x))) return false;
  if (cubic && on_border) {
    double q[9] = {0, 0, 0, 0, 0, 0, 0, 0, 0};
    if (solve_height<5>(S, T, q)) std::copy(q, q + 5, x);
  }
  Vec3 nn = n - x[0] * u0 - x[1] * w0;
  double l = nn.norm();
  if (!(l > 0)) return false;
  const double g = 1 / std::sqrt(1 + x[0] * x[0] + x[1] * x[1]);
  const double inv2 = inv * inv;
  double C0[4];
  for (int k = 0; k < 4; ++k) C0[k] = cubic ? -x[5 + k] * inv2 : 0.0;
  n = nn / l;
  u = any_tangent(n);
  w = n.cross(u);
  project_II(u0, w0, -x[2] * inv * g, -x[3] * inv * g, -x[4] * inv * g, u, w, ku, kuv, kv);
  CurvatureDerivative c = project_C(u0, w0, C0, u, w);
  C[0] = c.a, C[1] = c.b, C[2] = c.c, C[3] = c.d;
  return true;
}

}  // namespace

static Curvature compute_curvature_facefit(const TriMesh& mesh, const CurvatureOptions& opt,
                                           const VertexFaces& vf, std::vector<Vec3> normals);

static Curvature compute_curvature_jets(const TriMesh& mesh, const CurvatureOptions& opt, const VertexFaces& vf,
                                        std::vector<Vec3> normals) {
  const int nv = mesh.n_vertices();
  Curvature out;
  out.normal = std::move(normals);
  report(opt.progress, 20, "Voronoi areas");
  {
    auto ca = corner_areas(mesh);
    sized(out.point_area, nv);
#pragma omp parallel for schedule(static)
    for (int v = 0; v < nv; ++v) {
      double a = 0;
      for (int k = vf.offset[v]; k < vf.offset[v + 1]; ++k) a += ca[vf.face[k]][vf.corner[k]];
      out.point_area[v] = a;
    }
  }
  out.degenerate_faces = count_degenerate_faces(mesh);
  sized(out.dir1, nv, Vec3(Vec3::Zero()));
  sized(out.dir2, nv, Vec3(Vec3::Zero()));
  sized(out.k1, nv);
  sized(out.k2, nv);
  if (opt.derivatives) sized(out.dcurv, nv);
  std::vector<char> bad(nv, 0);
  report(opt.progress, 35, "Fitting local jets");
  std::vector<std::vector<int>> marks = per_thread(size_t(nv), 0);
#pragma omp parallel
  {
    std::vector<int> nb, &mark = marks[size_t(omp_get_thread_num())];
    std::vector<double> buf;
    nb.reserve(64);
#pragma omp for schedule(dynamic, 4096)
    for (int v = 0; v < nv; ++v) {
      Vec3 n = out.normal[v], u, w;
      double ku = 0, kuv = 0, kv = 0, C[4] = {0, 0, 0, 0};
      const bool on_border = two_ring(mesh, vf, v, nb, mark);
      bool ok = out.point_area[v] > 0 && jet_at(mesh, v, nb, on_border, buf, n, ku, kuv, kv, u, w, C);
      if (!ok) {
        bad[v] = 1;
        out.dir1[v] = any_tangent(out.normal[v]);
        out.dir2[v] = out.normal[v].cross(out.dir1[v]);
        continue;
      }
      out.normal[v] = n;
      diagonalize(u, w, n, ku, kuv, kv, out.k1[v], out.k2[v], out.dir1[v], out.dir2[v]);
      if (opt.derivatives) out.dcurv[v] = project_C(u, w, C, out.dir1[v], out.dir2[v]);
    }
  }
  for (int v = 0; v < nv; ++v)
    if (bad[v]) out.bad_vertices.push_back(v);
  report(opt.progress, 100, "Curvature done");
  return out;
}

double feature_width(const TriMesh& mesh, const Curvature& c, const MeshScale& scale, const MeshTopology* topology) {
  if (c.dcurv.size() != c.k1.size() || c.k1.empty()) return 0;
  const VertexRing border = topology ? VertexRing() : boundary_rings(mesh, vertex_faces(mesh));
  const VertexRing& b = topology ? topology->border : border;
  std::vector<double> k, d;
  for (size_t v = 0; v < c.k1.size(); ++v) {
    if (b.offset[v + 1] > b.offset[v]) continue;
    if (!scale.counts.empty() && !scale.counts[v]) continue;
    const CurvatureDerivative& C = c.dcurv[v];
    k.push_back(std::max(std::abs(c.k1[v]), std::abs(c.k2[v])));
    d.push_back(std::sqrt(C.a * C.a + 3 * C.b * C.b + 3 * C.c * C.c + C.d * C.d));
  }
  const double kq = percentile(k, 0.99), dq = percentile(d, 0.99);
  return dq > 0 && std::isfinite(kq / dq) ? kq / dq : 0;
}

// compute_curvature on a surface its caller has checked (require_triangles).
static Curvature compute_checked_curvature(const Surface& input, const CurvatureOptions& opt);

ScaledCurvature curvature_at_scale(const Surface& surface, const Length& presmoothing, CurvatureEstimator estimator,
                                   Progress progress) {
  surface.require_triangles();
  ScaledCurvature out;
  report(progress, 0, "Vertex adjacency");
  out.topology = surface.shared_topology();
  report(progress, 2, "Scale and noise level");
  out.scale = surface.scale();
  out.noise = surface.noise();  // refuses a mesh without usable edge length
  presmoothing.check("Pre-smoothing", 0, 100, out.scale.edge);
  out.presmoothing = presmoothing.resolve(out.scale.edge, automatic_presmoothing(out.noise, out.scale));
  if (out.presmoothing > 0) report(progress, 5, "Pre-smoothing");
  const Surface at = smoothed_surface(surface, out.presmoothing);
  out.curvature = at.curvature(estimator, true, progress);
  return out;
}

ScaledCurvature curvature_at_scale(const TriMesh& mesh, const Length& presmoothing, CurvatureEstimator estimator,
                                   Progress progress) {
  return curvature_at_scale(Surface::borrow(mesh), presmoothing, estimator, progress);
}

Curvature compute_curvature(const Surface& surface, const CurvatureOptions& opt) {
  surface.require_triangles();
  return compute_checked_curvature(surface, opt);
}

Curvature compute_curvature(const TriMesh& input, const CurvatureOptions& opt) {
  require_triangles(input);
  return compute_checked_curvature(Surface::borrow(input), opt);
}

static Curvature compute_checked_curvature(const Surface& input, const CurvatureOptions& opt) {
  count_work(Work::Curvature);
  const VertexFaces& vf = input.topology().faces;  // the run's (its building is reported by curvature_at_scale)
  // Pre-smoothing: the curvature of a diffused copy of the surface is reported at the
  // original vertices.
  if (opt.smoothing_scale > 0) report(opt.progress, 5, "Pre-smoothing");
  const Surface at = smoothed_surface(input, opt.smoothing_scale);
  report(opt.progress, 10, "Normals and Voronoi areas");
  std::vector<Vec3> normals = vertex_normals(at.mesh(), vf);
  if (opt.estimator == CurvatureEstimator::Jet) return compute_curvature_jets(at.mesh(), opt, vf, std::move(normals));
  return compute_curvature_facefit(at.mesh(), opt, vf, std::move(normals));
}

// The per-face fit (Rusinkiewicz 2004) in four steps: a frame and II per face, II averaged at
// the vertices and diagonalised, C per face from the vertices' II, C averaged at the vertices.

// Step 1: per face a tangent frame, the mixed corner areas and II fitted to the normal
// differences along the edges (dn = II e). Returns the number of degenerate faces.
static long long fit_face_II(const TriMesh& mesh, const std::vector<Vec3>& normal, std::vector<FaceFrame>& ff) {
  const int nf = mesh.n_faces();
  long long degenerate = 0;
#pragma omp parallel for schedule(static) reduction(+ : degenerate)
  for (int i = 0; i < nf; ++i) {
    const auto& f = mesh.faces[i];
    Vec3 e[3] = {mesh.vertices[f[2]] - mesh.vertices[f[1]], mesh.vertices[f[0]] - mesh.vertices[f[2]],
                 mesh.vertices[f[1]] - mesh.vertices[f[0]]};
    FaceFrame& fr = ff[i];
    Vec3 n = e[0].cross(e[1]);
    double nl = n.norm(), tl = e[0].norm();
    if (!(nl > 0) || !(tl > 0) || !std::isfinite(nl)) {
      ++degenerate;
      std::fill(std::begin(fr.area), std::end(fr.area), 0.f);
      std::fill(std::begin(fr.II), std::end(fr.II), 0.f);
      continue;
    }
    Vec3 t = e[0] / tl;
    n /= nl;
    Vec3 b = n.cross(t);
    put(fr.t, t);
    put(fr.b, b);
    double c[3];
    mixed_corner_areas(e, 0.5 * nl, c);
    for (int j = 0; j < 3; ++j) fr.area[j] = float(c[j]);
    // Least-squares II from normal differences along the edges: dn = II e.
    double w00 = 0, w01 = 0, w22 = 0, m0 = 0, m1 = 0, m2 = 0;
    for (int j = 0; j < 3; ++j) {
      double u = e[j].dot(t), v = e[j].dot(b);
      w00 += u * u;
      w01 += u * v;
      w22 += v * v;
      Vec3 dn = normal[f[prev3(j)]] - normal[f[next3(j)]];
      double dnu = dn.dot(t), dnv = dn.dot(b);
      m0 += dnu * u;
      m1 += dnu * v + dnv * u;
      m2 += dnv * v;
    }
    Eigen::Matrix3d w;
    w << w00, w01, 0, w01, w00 + w22, w01, 0, w01, w22;
    Eigen::Vector3d x = w.ldlt().solve(Eigen::Vector3d(m0, m1, m2));
    if (!x.allFinite()) x.setZero();
    for (int j = 0; j < 3; ++j) fr.II[j] = float(x[j]);
  }
  return degenerate;
}

// Step 2: II averaged over the faces around each vertex (weighted by corner area) and
// diagonalised. Vertices without area, or whose curvature is not finite, are marked bad.
static void principal_curvatures(const VertexFaces& vf, const std::vector<FaceFrame>& ff, Curvature& out) {
  const int nv = static_cast<int>(out.normal.size());
  sized(out.dir1, nv, Vec3(Vec3::Zero()));
  sized(out.dir2, nv, Vec3(Vec3::Zero()));
  sized(out.k1, nv);
  sized(out.k2, nv);
  sized(out.point_area, nv);
  std::vector<char> bad(nv, 0);
#pragma omp parallel for schedule(static)
  for (int v = 0; v < nv; ++v) {
    const Vec3& n = out.normal[v];
    // Initial frame: any tangent direction.
    Vec3 u = any_tangent(n), w = n.cross(u);
    double ku = 0, kuv = 0, kv = 0, A = 0;
    for (int k = vf.offset[v]; k < vf.offset[v + 1]; ++k) {
      const FaceFrame& fr = ff[vf.face[k]];
      double a = fr.area[vf.corner[k]];
      if (!(a > 0)) continue;
      double cu, cuv, cv;
      project_II(v3(fr.t), v3(fr.b), fr.II[0], fr.II[1], fr.II[2], u, w, cu, cuv, cv);
      ku += a * cu;
      kuv += a * cuv;
      kv += a * cv;
      A += a;
    }
    out.point_area[v] = A;
    if (!(A > 0)) {
      bad[v] = 1;
      out.dir1[v] = u;
      out.dir2[v] = w;
      continue;
    }
    ku /= A;
    kuv /= A;
    kv /= A;
    diagonalize(u, w, n, ku, kuv, kv, out.k1[v], out.k2[v], out.dir1[v], out.dir2[v]);
    if (!std::isfinite(out.k1[v]) || !std::isfinite(out.k2[v])) {
      out.k1[v] = out.k2[v] = 0;
      bad[v] = 1;
    }
  }
  for (int v = 0; v < nv; ++v)
    if (bad[v]) out.bad_vertices.push_back(v);
}

// Step 3: per face the derivative tensor fitted to the differences of the vertices' II along the
// edges.
static void fit_face_C(const TriMesh& mesh, const Curvature& out, std::vector<FaceFrame>& ff) {
  const int nf = mesh.n_faces();
#pragma omp parallel for schedule(static)
  for (int i = 0; i < nf; ++i) {
    FaceFrame& fr = ff[i];
    std::fill(std::begin(fr.C), std::end(fr.C), 0.f);
    if (!(fr.area[0] + fr.area[1] + fr.area[2] > 0)) continue;
    const auto& f = mesh.faces[i];
    Vec3 t = v3(fr.t), b = v3(fr.b);
    double fc[3][3];  // vertex II in the face frame
    for (int j = 0; j < 3; ++j) {
      int v = f[j];
      project_II(out.dir1[v], out.dir2[v], out.k1[v], 0, out.k2[v], t, b, fc[j][0], fc[j][1], fc[j][2]);
    }
    Vec3 e[3] = {mesh.vertices[f[2]] - mesh.vertices[f[1]], mesh.vertices[f[0]] - mesh.vertices[f[2]],
                 mesh.vertices[f[1]] - mesh.vertices[f[0]]};
    double w00 = 0, w01 = 0, w33 = 0;
    Eigen::Vector4d m = Eigen::Vector4d::Zero();
    for (int j = 0; j < 3; ++j) {
      double d0 = fc[prev3(j)][0] - fc[next3(j)][0], d1 = fc[prev3(j)][1] - fc[next3(j)][1],
             d2 = fc[prev3(j)][2] - fc[next3(j)][2];
      double u = e[j].dot(t), v = e[j].dot(b);
      w00 += u * u;
      w01 += u * v;
      w33 += v * v;
      m[0] += u * d0;
      m[1] += v * d0 + 2 * u * d1;
      m[2] += 2 * v * d1 + u * d2;
      m[3] += v * d2;
    }
    Eigen::Matrix4d w;
    w << w00, w01, 0, 0,  //
        w01, 2 * w00 + w33, 2 * w01, 0,  //
        0, 2 * w01, w00 + 2 * w33, w01,  //
        0, 0, w01, w33;
    Eigen::Vector4d x = w.ldlt().solve(m);
    if (!x.allFinite()) x.setZero();
    for (int j = 0; j < 4; ++j) fr.C[j] = float(x[j]);
  }
}

// Step 4: C averaged at the vertices in their principal frames.
static void vertex_derivatives(const VertexFaces& vf, const std::vector<FaceFrame>& ff, Curvature& out) {
  const int nv = static_cast<int>(out.normal.size());
  sized(out.dcurv, nv);
#pragma omp parallel for schedule(static)
  for (int v = 0; v < nv; ++v) {
    double A = out.point_area[v];
    if (!(A > 0)) continue;
    CurvatureDerivative acc;
    for (int k = vf.offset[v]; k < vf.offset[v + 1]; ++k) {
      const FaceFrame& fr = ff[vf.face[k]];
      double a = fr.area[vf.corner[k]];
      if (!(a > 0)) continue;
      double C[4] = {fr.C[0], fr.C[1], fr.C[2], fr.C[3]};
      CurvatureDerivative p = project_C(v3(fr.t), v3(fr.b), C, out.dir1[v], out.dir2[v]);
      acc.a += a * p.a;
      acc.b += a * p.b;
      acc.c += a * p.c;
      acc.d += a * p.d;
    }
    acc.a /= A;
    acc.b /= A;
    acc.c /= A;
    acc.d /= A;
    if (!(std::isfinite(acc.a) && std::isfinite(acc.b) && std::isfinite(acc.c) && std::isfinite(acc.d)))
      acc = CurvatureDerivative{};
    out.dcurv[v] = acc;
  }
}

static Curvature compute_curvature_facefit(const TriMesh& mesh, const CurvatureOptions& opt, const VertexFaces& vf,
                                           std::vector<Vec3> normals) {
  Curvature out;
  out.normal = std::move(normals);
  std::vector<FaceFrame> ff;
  sized(ff, mesh.n_faces());
  out.degenerate_faces = fit_face_II(mesh, out.normal, ff);
  report(opt.progress, 35, "Principal curvatures");
  principal_curvatures(vf, ff, out);
  if (opt.derivatives) {
    report(opt.progress, 60, "Curvature derivatives");
    fit_face_C(mesh, out, ff);
    report(opt.progress, 80, "Curvature derivatives");
    vertex_derivatives(vf, ff, out);
  }
  report(opt.progress, 100, "Curvature done");
  return out;
}

}  // namespace reliefkit
