#include "reliefkit/curvature.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

#include "reliefkit/smoothing.h"

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
  std::vector<Vec3> n(nv);
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
  std::vector<std::array<double, 3>> ca(nf);
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

// Collects the two-ring of v (without v) into `out` (sorted, unique).
inline void two_ring(const VertexRing& ring, int v, std::vector<int>& out) {
  out.clear();
  for (int k = ring.offset[v]; k < ring.offset[v + 1]; ++k) {
    int u = ring.vertex[k];
    out.push_back(u);
    for (int l = ring.offset[u]; l < ring.offset[u + 1]; ++l) out.push_back(ring.vertex[l]);
  }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  auto it = std::lower_bound(out.begin(), out.end(), v);
  if (it != out.end() && *it == v) out.erase(it);
}

// Least-squares osculating jet at one vertex: the height over the tangent plane of `n`,
//   z = g1 x + g2 y + (A x^2 + 2B xy + C y^2)/2 + (D x^3 + 3E x^2 y + 3F x y^2 + G y^3)/6,
// fitted to the neighbours (cubic with >= 12 of them, quadratic with >= 6). The tangent plane is
// refitted once with the gradient (g1, g2), which makes the curvature estimate second-order
// accurate on irregular meshes. Returns false if no fit was possible.
bool jet_at(const TriMesh& mesh, int v, const std::vector<int>& nb, Vec3& n, double& ku, double& kuv,
            double& kv, Vec3& u, Vec3& w, double C[4]) {
  const int m = static_cast<int>(nb.size());
  if (m < 6) return false;
  const bool cubic = m >= 12;
  const int nu = cubic ? 9 : 5;
  const Vec3& p = mesh.vertices[v];
  double s2 = 0;
  for (int j : nb) s2 += (mesh.vertices[j] - p).squaredNorm();
  double s = std::sqrt(s2 / m);
  if (!(s > 0) || !std::isfinite(s)) return false;
  double inv = 1 / s;
  Eigen::Matrix<double, 9, 1> x = Eigen::Matrix<double, 9, 1>::Zero();
  for (int iter = 0; iter < 2; ++iter) {
    u = any_tangent(n);
    w = n.cross(u);
    Eigen::Matrix<double, 9, 9> AtA = Eigen::Matrix<double, 9, 9>::Zero();
    Eigen::Matrix<double, 9, 1> Atb = Eigen::Matrix<double, 9, 1>::Zero();
    for (int j : nb) {
      Vec3 d = (mesh.vertices[j] - p) * inv;
      double X = d.dot(u), Y = d.dot(w), Z = d.dot(n);
      Eigen::Matrix<double, 9, 1> r;
      r << X, Y, 0.5 * X * X, X * Y, 0.5 * Y * Y, X * X * X / 6, 0.5 * X * X * Y, 0.5 * X * Y * Y, Y * Y * Y / 6;
      AtA.topLeftCorner(nu, nu).selfadjointView<Eigen::Lower>().rankUpdate(r.head(nu));
      Atb.head(nu) += r.head(nu) * Z;
    }
    AtA.topLeftCorner(nu, nu) = AtA.topLeftCorner(nu, nu).selfadjointView<Eigen::Lower>();
    Eigen::LDLT<Eigen::MatrixXd> ldlt(AtA.topLeftCorner(nu, nu));
    if (ldlt.info() != Eigen::Success) return false;
    x.head(nu) = ldlt.solve(Atb.head(nu));
    if (!x.head(nu).allFinite()) return false;
    if (iter == 0) {
      Vec3 nn = n - x[0] * u - x[1] * w;
      double l = nn.norm();
      if (!(l > 0)) return false;
      n = nn / l;
    }
  }
  // Remaining tilt (second order) is corrected through the metric: II ~ Hess / sqrt(1+|g|^2).
  double g = 1 / std::sqrt(1 + x[0] * x[0] + x[1] * x[1]);
  ku = -x[2] * inv * g;
  kuv = -x[3] * inv * g;
  kv = -x[4] * inv * g;
  double inv2 = inv * inv;
  for (int k = 0; k < 4; ++k) C[k] = cubic ? -x[5 + k] * inv2 : 0.0;
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
  report(opt.progress, 20, "Vertex neighbourhoods");
  VertexRing ring = vertex_rings(mesh, vf);
  auto ca = corner_areas(mesh);
  out.point_area.assign(nv, 0);
  for (size_t f = 0; f < mesh.faces.size(); ++f)
    for (int j = 0; j < 3; ++j) out.point_area[mesh.faces[f][j]] += ca[f][j];
  for (const auto& c : ca)
    if (!(c[0] + c[1] + c[2] > 0)) ++out.degenerate_faces;
  out.dir1.resize(nv);
  out.dir2.resize(nv);
  out.k1.assign(nv, 0);
  out.k2.assign(nv, 0);
  if (opt.derivatives) out.dcurv.assign(nv, CurvatureDerivative{});
  std::vector<char> bad(nv, 0);
  report(opt.progress, 35, "Fitting local jets");
#pragma omp parallel
  {
    std::vector<int> nb;
    nb.reserve(64);
#pragma omp for schedule(dynamic, 1024)
    for (int v = 0; v < nv; ++v) {
      Vec3 n = out.normal[v], u, w;
      double ku = 0, kuv = 0, kv = 0, C[4] = {0, 0, 0, 0};
      two_ring(ring, v, nb);
      bool ok = out.point_area[v] > 0 && jet_at(mesh, v, nb, n, ku, kuv, kv, u, w, C);
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

Curvature compute_curvature(const TriMesh& input, const CurvatureOptions& opt) {
  require_triangles(input);
  report(opt.progress, 0, "Vertex adjacency");
  VertexFaces vf = vertex_faces(input);
  // Pre-smoothing: the curvature of a diffused copy of the surface is reported at the
  // original vertices.
  TriMesh smoothed;
  if (opt.smoothing_scale > 0) {
    report(opt.progress, 5, "Pre-smoothing");
    smoothed.faces = input.faces;
    smoothed.vertices = input.vertices;
    diffuse(input, vertex_rings(input, vf), opt.smoothing_scale, smoothed.vertices);
  }
  const TriMesh& mesh = opt.smoothing_scale > 0 ? smoothed : input;
  report(opt.progress, 10, "Normals and Voronoi areas");
  std::vector<Vec3> normals = vertex_normals(mesh, vf);
  if (opt.estimator == CurvatureEstimator::Jet) return compute_curvature_jets(mesh, opt, vf, std::move(normals));
  return compute_curvature_facefit(mesh, opt, vf, std::move(normals));
}

static Curvature compute_curvature_facefit(const TriMesh& mesh, const CurvatureOptions& opt, const VertexFaces& vf,
                                           std::vector<Vec3> normals) {
  const int nv = mesh.n_vertices(), nf = mesh.n_faces();
  Curvature out;
  out.normal = std::move(normals);
  std::vector<FaceFrame> ff(nf);
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
      Vec3 dn = out.normal[f[prev3(j)]] - out.normal[f[next3(j)]];
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
  out.degenerate_faces = degenerate;
  report(opt.progress, 35, "Principal curvatures");

  out.dir1.resize(nv);
  out.dir2.resize(nv);
  out.k1.assign(nv, 0);
  out.k2.assign(nv, 0);
  out.point_area.assign(nv, 0);
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

  if (opt.derivatives) {
    report(opt.progress, 60, "Curvature derivatives");
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
    report(opt.progress, 80, "Curvature derivatives");
    out.dcurv.assign(nv, CurvatureDerivative{});
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
  report(opt.progress, 100, "Curvature done");
  return out;
}

}  // namespace reliefkit
