// Accuracy and cost of the curvature-derivative tensor: ReliefKit's estimators against CGAL's
// jet fitting (Cazals & Pouget, CGAL::Monge_via_jet_fitting, degree-3 jet and Monge form) on a
// Monge patch whose tensor at the origin is known, over regular and jittered triangulations,
// and the time of both on a ~100 K-face mesh.
//   build/bench/bench_derivatives
#define CGAL_EIGEN3_ENABLED 1
#include <CGAL/Monge_via_jet_fitting.h>
#include <CGAL/Simple_cartesian.h>
#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <vector>

#include "reliefkit/base/curvature.h"
#include "shapes.h"

using namespace reliefkit;
using K = CGAL::Simple_cartesian<double>;
using Fitter = CGAL::Monge_via_jet_fitting<K>;

namespace {

struct Tensor {
  double a, b, c, d;
};

// Components in the world (x, y) frame of a cubic form given in the orthonormal frame (d1, d2).
Tensor to_xy(const Tensor& t, const Vec3& d1, const Vec3& d2) {
  double T[2][2][2] = {{{t.a, t.b}, {t.b, t.c}}, {{t.b, t.c}, {t.c, t.d}}};
  auto form = [&](const Vec2& p, const Vec2& q, const Vec2& s) {
    double r = 0;
    for (int i = 0; i < 2; ++i)
      for (int j = 0; j < 2; ++j)
        for (int k = 0; k < 2; ++k) r += T[i][j][k] * p[i] * q[j] * s[k];
    return r;
  };
  Vec2 X(d1.x(), d2.x()), Y(d1.y(), d2.y());
  return {form(X, X, X), form(X, X, Y), form(X, Y, Y), form(Y, Y, Y)};
}

// Neighbourhood of v: its k-ring (vertex included), from the face adjacency.
std::vector<int> k_ring(const TriMesh& m, const VertexFaces& vf, int v, int k) {
  std::vector<int> ring{v}, frontier{v};
  thread_local std::vector<int> seen;  // stamps, so no per-call clearing
  thread_local int stamp = 0;
  if (seen.size() != m.vertices.size()) seen.assign(m.vertices.size(), 0), stamp = 0;
  ++stamp;
  seen[v] = stamp;
  for (int step = 0; step < k; ++step) {
    std::vector<int> next;
    for (int u : frontier)
      for (int i = vf.offset[u]; i < vf.offset[u + 1]; ++i)
        for (int w : m.faces[vf.face[i]])
          if (seen[w] != stamp) seen[w] = stamp, next.push_back(w), ring.push_back(w);
    frontier.swap(next);
  }
  return ring;
}

Tensor cgal_tensor(const TriMesh& m, const std::vector<int>& nb) {
  std::vector<K::Point_3> pts;
  for (int i : nb) pts.emplace_back(m.vertices[i].x(), m.vertices[i].y(), m.vertices[i].z());
  Fitter fit;
  Fitter::Monge_form mf = fit(pts.begin(), pts.end(), 3, 3);
  mf.comply_wrt_given_normal(K::Vector_3(0, 0, 1));
  auto d1 = mf.maximal_principal_direction(), d2 = mf.minimal_principal_direction();
  // CGAL's Monge form is the height along +z; ReliefKit's II is minus the Hessian (see curvature.h).
  Tensor t{-mf.coefficients()[2], -mf.coefficients()[3], -mf.coefficients()[4], -mf.coefficients()[5]};
  return to_xy(t, Vec3(d1.x(), d1.y(), d1.z()), Vec3(d2.x(), d2.y(), d2.z()));
}

double rel_err(const Tensor& t, const Tensor& ref) {
  return std::max({std::abs(t.a - ref.a) / std::abs(ref.a), std::abs(t.b - ref.b) / std::abs(ref.b),
                   std::abs(t.c - ref.c) / std::abs(ref.c), std::abs(t.d - ref.d) / std::abs(ref.d)});
}

double now() { return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count(); }

}  // namespace

int main() {
  const double p = -1.0, q = -0.3, A = 0.6, B = -0.4, C = 0.25, D = 0.5;
  const Tensor ref{-A, -B, -C, -D};
  std::printf("Derivative tensor at the origin of z = (p x^2 + q y^2)/2 + cubic [+ e (x^4 + x^2 y^2 + y^4)],\n"
              "100-cell grid on [-0.25, 0.25]^2; largest relative error of a, b, c, d (median of 9 meshes)\n");
  std::printf("%-10s %-8s %-44s %10s\n", "mesh", "quartic", "estimator", "max rel err");
  for (double e : {0.0, 2.0})
    for (double jitter : {0.0, 0.5}) {
      auto z = [&](double x, double y) {
        return 0.5 * (p * x * x + q * y * y) + (A * x * x * x + 3 * B * x * x * y + 3 * C * x * y * y + D * y * y * y) / 6 +
               e * (x * x * x * x + x * x * y * y + y * y * y * y);
      };
      std::vector<double> e_jet, e_face, e_cgal2, e_cgal3;
      for (uint32_t seed = 1; seed <= (jitter > 0 ? 9u : 1u); ++seed) {
        int o = -1;
        TriMesh m = rktest::height_field(z, 0.25, 100, jitter, seed, &o);
        for (auto est : {CurvatureEstimator::Jet, CurvatureEstimator::FaceFit}) {
          CurvatureOptions opt;
          opt.estimator = est;
          Curvature c = compute_curvature(m, opt);
          const auto& t = c.dcurv[o];
          Tensor w = to_xy({t.a, t.b, t.c, t.d}, c.dir1[o], c.dir2[o]);
          (est == CurvatureEstimator::Jet ? e_jet : e_face).push_back(rel_err(w, ref));
        }
        VertexFaces vf = vertex_faces(m);
        e_cgal2.push_back(rel_err(cgal_tensor(m, k_ring(m, vf, o, 2)), ref));
        e_cgal3.push_back(rel_err(cgal_tensor(m, k_ring(m, vf, o, 3)), ref));
      }
      const char* mesh = jitter > 0 ? "jittered" : "regular";
      std::printf("%-10s %-8g %-44s %10.4f\n", mesh, e, "ReliefKit jet fit (two-ring)", rktest::median(e_jet));
      std::printf("%-10s %-8g %-44s %10.4f\n", mesh, e, "ReliefKit per-face fit (Rusinkiewicz)", rktest::median(e_face));
      std::printf("%-10s %-8g %-44s %10.4f\n", mesh, e, "CGAL Monge_via_jet_fitting, two-ring", rktest::median(e_cgal2));
      std::printf("%-10s %-8g %-44s %10.4f\n", mesh, e, "CGAL Monge_via_jet_fitting, three-ring", rktest::median(e_cgal3));
    }

  TriMesh m = rktest::relief_torus(100000);
  VertexFaces vf = vertex_faces(m);
  double t0 = now();
  Curvature c = compute_curvature(m);
  double t_ours = now() - t0;
  t0 = now();
  double sink = 0;
#pragma omp parallel for schedule(dynamic, 256) reduction(+ : sink)
  for (int v = 0; v < m.n_vertices(); ++v) sink += cgal_tensor(m, k_ring(m, vf, v, 2)).a;
  double t_cgal = now() - t0;
  std::printf("\nTime on %d faces, %d threads: ReliefKit jet (curvature + derivatives, whole mesh) %.3f s; "
              "CGAL jet fitting at every vertex (two-ring, ring gathering included) %.3f s (%.0fx)\n",
              m.n_faces(), omp_get_max_threads(), t_ours, t_cgal, t_cgal / t_ours);
  return sink == 12345.678 && c.k1.empty();
}
