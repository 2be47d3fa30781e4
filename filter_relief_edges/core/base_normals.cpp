#include "base_normals.h"

#include "reliefkit/scale.h"

#include <algorithm>
#include <cmath>

#include "reliefkit/curvature.h"
#include "reliefkit/memory.h"

namespace reliefkit {

double automatic_base_scale(const MeshScale& s) {
  return kDefaultBaseScaleEdges * s.edge;
}

double default_base_scale(const TriMesh& mesh) { return automatic_base_scale(mesh_scale(mesh)); }

BaseNormals estimate_base_normals(const TriMesh& mesh, const std::vector<Vec3>& n0, const BaseNormalOptions& opt) {
  require_triangles(mesh);
  const int nv = mesh.n_vertices();
  if (int(n0.size()) != nv) throw InputError("base normals: one surface normal per vertex is needed");
  if (!(opt.scale > 0) || !std::isfinite(opt.scale)) throw InputError("base normals: the scale must be positive");
  const double t = 0.5 * opt.scale * opt.scale;
  if (opt.progress) opt.progress(0, "Base normals: system");
  VertexFaces vf = vertex_faces(mesh);
  VertexRing ring = vertex_rings(mesh, vf);
  auto ca = corner_areas(mesh);
  // Rows of A = M + t K in the ring's CSR layout: off-diagonal -t w_vu, diagonal M_v + t sum w.
  std::vector<double> off, diag;
  sized(off, ring.vertex.size());
  sized(diag, size_t(nv));
#pragma omp parallel for schedule(static)
  for (int v = 0; v < nv; ++v) {
    const int b = ring.offset[v], e = ring.offset[v + 1];
    for (int k = b; k < e; ++k) off[k] = 0;
    double area = 0;
    for (int k = vf.offset[v]; k < vf.offset[v + 1]; ++k) {
      const auto& f = mesh.faces[vf.face[k]];
      const int c = vf.corner[k];
      area += ca[vf.face[k]][c];
      // Edge (v, f[c+1]) is opposite corner c+2 and edge (v, f[c+2]) opposite corner c+1.
      for (int side = 1; side <= 2; ++side) {
        const int u = f[(c + side) % 3], o = f[(c + 3 - side) % 3];
        Vec3 a = mesh.vertices[v] - mesh.vertices[o], bb = mesh.vertices[u] - mesh.vertices[o];
        double s = a.cross(bb).norm();
        double cot = s > 0 ? a.dot(bb) / s : 0;
        if (!std::isfinite(cot) || cot < 0) cot = 0;
        if (e - b > 32) {  // long rings are sorted (vertex_rings): binary search, so a fan stays linear
          const int* it = std::lower_bound(ring.vertex.data() + b, ring.vertex.data() + e, u);
          if (it != ring.vertex.data() + e && *it == u) off[it - ring.vertex.data()] += 0.5 * cot;
        } else {
          for (int j = b; j < e; ++j)
            if (ring.vertex[j] == u) {
              off[j] += 0.5 * cot;
              break;
            }
        }
      }
    }
    double sum = 0;
    for (int k = b; k < e; ++k) sum += off[k], off[k] *= -t;
    // Isolated or degenerate vertices keep their own normal (diagonal 1, no coupling).
    diag[v] = area > 0 ? area + t * sum : 1.0;
    if (!(area > 0))
      for (int k = b; k < e; ++k) off[k] = 0;
  }
  auto multiply = [&](const std::vector<Vec3>& x, std::vector<Vec3>& y) {
#pragma omp parallel for schedule(static)
    for (int v = 0; v < nv; ++v) {
      Vec3 s = diag[v] * x[v];
      for (int k = ring.offset[v]; k < ring.offset[v + 1]; ++k) s += off[k] * x[ring.vertex[k]];
      y[v] = s;
    }
  };
  // Right-hand side M N; start from N itself.
  std::vector<Vec3> x, r, z, p, q;
  for (auto* vec : {&x, &r, &z, &p, &q}) sized(*vec, size_t(nv), Vec3(Vec3::Zero()));
  std::vector<double> area(nv, 0.0);
  for (size_t f = 0; f < mesh.faces.size(); ++f)
    for (int j = 0; j < 3; ++j) area[mesh.faces[f][j]] += ca[f][j];
  Vec3 bnorm2 = Vec3::Zero();
  for (int v = 0; v < nv; ++v) {
    x[v] = n0[v].allFinite() ? n0[v] : Vec3(0, 0, 1);
    Vec3 b = (area[v] > 0 ? area[v] : 1.0) * x[v];
    r[v] = b;
    bnorm2 += b.cwiseProduct(b);
  }
  multiply(x, q);
  // Conjugate gradients, the three coordinates side by side (one pass over the matrix each).
  Vec3 rz = Vec3::Zero();
  for (int v = 0; v < nv; ++v) {
    r[v] -= q[v];
    z[v] = r[v] / diag[v];
    p[v] = z[v];
    rz += r[v].cwiseProduct(z[v]);
  }
  BaseNormals out;
  const double tol2 = opt.tolerance * opt.tolerance;
  for (int it = 0; it < opt.max_iterations; ++it) {
    multiply(p, q);
    double pq0 = 0, pq1 = 0, pq2 = 0;
#pragma omp parallel for schedule(static) reduction(+ : pq0, pq1, pq2)
    for (int v = 0; v < nv; ++v) pq0 += p[v].x() * q[v].x(), pq1 += p[v].y() * q[v].y(), pq2 += p[v].z() * q[v].z();
    const Vec3 pq(pq0, pq1, pq2);
    const Vec3 alpha = (pq.array() > 0).select(rz.cwiseQuotient(pq), Vec3::Zero());
    double rr0 = 0, rr1 = 0, rr2 = 0, rz0 = 0, rz1 = 0, rz2 = 0;
#pragma omp parallel for schedule(static) reduction(+ : rr0, rr1, rr2, rz0, rz1, rz2)
    for (int v = 0; v < nv; ++v) {
      x[v] += alpha.cwiseProduct(p[v]);
      r[v] -= alpha.cwiseProduct(q[v]);
      z[v] = r[v] / diag[v];
      rr0 += r[v].x() * r[v].x(), rr1 += r[v].y() * r[v].y(), rr2 += r[v].z() * r[v].z();
      rz0 += r[v].x() * z[v].x(), rz1 += r[v].y() * z[v].y(), rz2 += r[v].z() * z[v].z();
    }
    const Vec3 rr(rr0, rr1, rr2), rz_new(rz0, rz1, rz2);
    out.iterations = it + 1;
    double rel = 0;
    for (int k = 0; k < 3; ++k) rel = std::max(rel, bnorm2[k] > 0 ? rr[k] / bnorm2[k] : 0.0);
    out.residual = std::sqrt(rel);
    if (rel <= tol2) break;
    const Vec3 beta = (rz.array() > 0).select(rz_new.cwiseQuotient(rz), Vec3::Zero());
    rz = rz_new;
#pragma omp parallel for schedule(static)
    for (int v = 0; v < nv; ++v) p[v] = z[v] + beta.cwiseProduct(p[v]);
    if (opt.progress && it % 10 == 0) opt.progress(std::min(95, 10 + it), "Base normals: diffusion");
  }
  out.converged = out.residual <= opt.tolerance;
  out.normal.swap(x);
  for (int v = 0; v < nv; ++v) {
    double l = out.normal[v].norm();
    out.normal[v] = (l > 0 && std::isfinite(l)) ? Vec3(out.normal[v] / l) : (n0[v].allFinite() ? n0[v] : Vec3(0, 0, 1));
  }
  return out;
}

}  // namespace reliefkit
