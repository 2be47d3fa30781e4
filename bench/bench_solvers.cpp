// Benchmark of the base-normal solve (reliefkit/base/solvers.h) on the relief torus or on scans: Eigen's conjugate
// gradients, CHOLMOD's Cholesky factorization and the automatic choice, at base scales of 15, 60
// and 227 edge lengths (the default, a wide one, and what Relief Edges chose at 10 M faces).
// Each solve's accuracy is printed beside its time: the residual measured on the result, and the
// median / largest angle between its normals and those of a Cholesky solve (exact to rounding),
// so a fast but unconverged solve shows as such. Mesh files given instead (real scans) are solved
// at the default base scale.
//   build/bench/bench_solvers [--sizes 1000000] [--repeat 1] [scan.ply ...]
#include <omp.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "reliefkit/relief_edges/base_normals.h"
#include "bench_util.h"
#include "reliefkit/base/curvature.h"
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
    compare_solvers(rktest::relief_torus(target), {15.0, 60.0, 227.0}, args.repeat);
  }
}
