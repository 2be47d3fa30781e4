// Benchmark of the base-normal solve (reliefkit/base/solvers.h) on the relief torus or on scans: Eigen's conjugate
// gradients, CHOLMOD's Cholesky factorization and the automatic choice, at base scales of 15, 60
// and 227 edge lengths (the default, a wide one, and what Relief Edges chose at 10 M faces).
// Each solve's accuracy is printed beside its time: the residual measured on the result, and the
// median / largest angle between its normals and those of a Cholesky solve (exact to rounding),
// so a fast but unconverged solve shows as such. Mesh files given instead (real scans) are solved
// at the default base scale.
// On the torus it then times the multilevel cycle against two levels (set-up and iterations
// apart), and a Hermitian system solved with complex unknowns against its real form.
//   build/bench/bench_solvers [--sizes 1000000] [--repeat 1] [scan.ply ...]
#include <omp.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdio>
#include <string>
#include <vector>

#include "reliefkit/relief_edges/base_normals.h"
#include "bench_util.h"
#include "reliefkit/base/curvature.h"
#include "reliefkit/base/laplacian.h"
#include "reliefkit/base/multilevel.h"
#include "reliefkit/base/solvers.h"
#include "reliefkit/base/repair.h"
#include "mesh_files.h"
#include "shapes.h"

using namespace reliefkit;

namespace {

// Every solver at every scale on one mesh; each row with its accuracy against a Cholesky solve.
void compare_solvers(const TriMesh& m, const std::vector<double>& scales_in_edges, int repeat) {
  const double h = mesh_scale(m).edge;
  const std::vector<Vec3> n = vertex_normals(m, vertex_faces(m));
  const double mfaces = m.faces.size() / 1e6;
  for (double edges : scales_in_edges) {
    BaseNormalOptions o;
    o.scale = edges * h;
    o.method = SolverMethod::Direct;
    const BaseNormals exact = estimate_base_normals(m, n, o);
    const std::pair<const char*, SolverMethod> solvers[] = {
        {"auto", SolverMethod::Auto}, {"CG", SolverMethod::Iterative}, {"Cholesky", SolverMethod::Direct},
        {"multilevel", SolverMethod::Multilevel}};
    for (const auto& [name, method] : solvers) {
      o.method = method;
      double best = 1e30, peak = 0;
      BaseNormals b;
      for (int r = 0; r < repeat; ++r) {
        rkbench::PeakMemory mem;
        mem.start();
        const double t0 = rkbench::now();
        b = estimate_base_normals(m, n, o);
        best = std::min(best, rkbench::now() - t0);
        peak = std::max(peak, mem.grown_mib());
      }
      std::vector<double> angle(b.normal.size());
      for (size_t v = 0; v < angle.size(); ++v)
        angle[v] = std::acos(std::clamp(b.normal[v].dot(exact.normal[v]), -1.0, 1.0)) * 180 / M_PI;
      const double mx = *std::max_element(angle.begin(), angle.end());
      std::nth_element(angle.begin(), angle.begin() + angle.size() / 2, angle.end());
      std::printf("%-9zu %-6.0f %-10s %8.3f %9.0f %8.2f  %-52s %.3f / %.3f\n", m.faces.size(), edges, name, best, peak,
                  best / mfaces, b.solve.summary().c_str(), angle[angle.size() / 2], mx);
      std::fflush(stdout);
    }
  }
}

// The base-normal system M - tL (clamped weights) at `edges` edge lengths, as estimate_base_normals builds it.
Eigen::SparseMatrix<double> heat_step(const TriMesh& m, double edges, Eigen::VectorXd& mass) {
  LaplacianOptions lo;
  lo.clamp_negative = true;
  LaplacianResult lap = cotangent_laplacian(m, lo);
  const double h = mesh_scale(m).edge, t = 0.5 * (edges * h) * (edges * h);
  Eigen::SparseMatrix<double> A = -t * lap.L;
  for (int v = 0; v < A.rows(); ++v) A.coeffRef(v, v) += lap.mass[v] > 0 ? lap.mass[v] : 1.0;
  mass = lap.mass;
  return A;
}

// The V-cycle through as many levels as reach kLargestFactorizedLevel against the two-level cycle
// (every aggregate of the finest level factorized), set-up and iterations timed apart, on the
// base normals' right-hand sides.
void compare_levels(const TriMesh& m, const std::vector<double>& scales_in_edges) {
  const std::vector<Vec3> n = vertex_normals(m, vertex_faces(m));
  std::printf("%-9s %-6s %-24s %8s %8s %8s %10s %8s\n", "faces", "scale", "levels (factorized)", "set-up s",
              "solve s", "total s", "iterations", "residual");
  for (double edges : scales_in_edges) {
    Eigen::VectorXd mass;
    const Eigen::SparseMatrix<double> A = heat_step(m, edges, mass);
    Eigen::MatrixXd B(A.rows(), 3);
    for (int v = 0; v < A.rows(); ++v) B.row(v) = (mass[v] > 0 ? mass[v] : 1.0) * n[size_t(v)].transpose();
    for (int largest : {kLargestFactorizedLevel, int(A.rows())}) {
      const double t0 = rkbench::now();
      const MultilevelPreconditioner cycle(A, largest);
      const double t1 = rkbench::now();
      Eigen::MatrixXd X = B;
      const int iterations = preconditioned_cg(cycle, B, X, 1e-3, 500);
      const double t2 = rkbench::now();
      const double residual = (A * X - B).norm() / B.norm();
      const std::string levels = std::to_string(cycle.levels()) + " (" + std::to_string(cycle.coarse_size()) + ")";
      std::printf("%-9zu %-6.0f %-24s %8.3f %8.3f %8.3f %10d %8.1e\n", m.faces.size(), edges, levels.c_str(), t1 - t0,
                  t2 - t1, t2 - t0, iterations, residual);
      std::fflush(stdout);
    }
  }
}

// A Hermitian system with complex couplings — the heat step at 15 edge lengths seen through unit
// phases on the vertices, D^H (M - tL) D, like the prominent field's connection Laplacian — solved
// by solve_hpd (complex unknowns, every loop on both cores) and by Eigen's conjugate gradients on
// its real form of twice the size (how the prominent field solved it until 4 Dec), to 1e-2.
void compare_hermitian(const TriMesh& m) {
  Eigen::VectorXd mass;
  const Eigen::SparseMatrix<double> S = heat_step(m, 15, mass);
  const int nv = int(S.rows());
  std::vector<std::complex<double>> phase(static_cast<size_t>(nv));
  for (int i = 0; i < nv; ++i) phase[size_t(i)] = std::polar(1.0, 2.4 * i);
  std::vector<Eigen::Triplet<std::complex<double>>> entries;
  for (int c = 0; c < nv; ++c)
    for (Eigen::SparseMatrix<double>::InnerIterator it(S, c); it; ++it)
      entries.emplace_back(int(it.row()), c, std::conj(phase[size_t(it.row())]) * it.value() * phase[size_t(c)]);
  HermitianMatrix A(nv, nv);
  A.setFromTriplets(entries.begin(), entries.end());
  Eigen::VectorXcd b(nv);
  for (int i = 0; i < nv; ++i) b[i] = mass[i] * std::polar(1.0, std::sin(0.001 * i));
  SolverOptions o;
  o.tolerance = 1e-2;
  o.max_iterations = 2000;
  Eigen::VectorXcd x;
  double t0 = rkbench::now();
  const SolveReport complex_cg = solve_hpd(A, b, x, o);
  const double complex_seconds = rkbench::now() - t0;
  const Eigen::SparseMatrix<double> R = real_form(A);
  Eigen::MatrixXd B(2 * nv, 1), X;
  for (int i = 0; i < nv; ++i) B(2 * i, 0) = b[i].real(), B(2 * i + 1, 0) = b[i].imag();
  o.method = SolverMethod::Iterative;
  t0 = rkbench::now();
  const SolveReport real_cg = solve_spd(R, B, X, o);
  const double real_seconds = rkbench::now() - t0;
  std::printf("%-9zu complex unknowns (solve_hpd)      %8.3f s  %s\n", m.faces.size(), complex_seconds,
              complex_cg.summary().c_str());
  std::printf("%-9zu real form, Eigen CG (solve_spd)   %8.3f s  %s\n", m.faces.size(), real_seconds,
              real_cg.summary().c_str());
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<std::string> scans;  // mesh files given after the options: solved at the default scale
  std::vector<char*> options{argv[0]};
  for (int i = 1; i < argc; ++i) {
    if (argv[i][0] == '-' && i + 1 < argc) {
      options.push_back(argv[i]);
      options.push_back(argv[++i]);
    } else {
      scans.push_back(argv[i]);
    }
  }
  rkbench::Args args = rkbench::parse_args(int(options.size()), options.data(), {1000000});
  std::printf("Base-normal solve, %d threads, best of %d runs\n", omp_get_max_threads(), args.repeat);
  std::printf("%-9s %-6s %-10s %8s %9s %8s  %-52s %s\n", "faces", "scale", "solver", "time s", "peak MiB", "s/M",
              "report", "angle to exact: median / max deg");
  if (!scans.empty()) {
    for (const std::string& path : scans) {
      std::printf("%s\n", path.c_str());
      compare_solvers(repair_for_computation(rktest::read_mesh(path).mesh).mesh, {kDefaultBaseScaleEdges}, args.repeat);
    }
    return 0;
  }
  for (long target : args.sizes) {
    std::printf("relief torus\n");
    const TriMesh torus = rktest::relief_torus(target);
    compare_solvers(torus, {15.0, 60.0, 227.0}, args.repeat);
    std::printf("\nMultilevel cycle against two levels, relief torus (one run each)\n");
    compare_levels(torus, {15.0, 60.0, 227.0});
    std::printf("\nHermitian system at 15 edge lengths, relief torus\n");
    compare_hermitian(torus);
  }
}
