// Benchmark of the prominent field, enhancement and coloring (reliefkit/prominent/prominent.h) on ~1 M faces:
// time, peak memory, and the accuracy of what was timed.
//   build/bench/bench_prominent [--sizes 1000000] [--repeat 1]
// Surface: the relief-edge benchmarks' cylinder with a raised and a sunken disc, 10 % noise; for
// the enhancement the discs' steps are eroded (tanh width 8 edge lengths at 1 M faces) and the
// accuracy is the RMS distance near the rims to the same relief with sharp steps (width 1.6).
// Field accuracy: median angle between the field and the true direction across the rims
// (unrolled radial direction) within two step widths of them.
#include <cmath>
#include <cstdio>
#include <string>
#include <omp.h>

#include "bench_util.h"
#include "reliefkit/base/angles.h"
#include "reliefkit/prominent/prominent.h"
#include "reliefs.h"
#include "shapes.h"

using namespace reliefkit;

namespace {

constexpr double kR1 = 0.4, kR2 = 0.3;  // the discs of rktest::discs_on_cylinder

// Distance in the unrolled (arc, z) plane to the nearest rim, and the unit direction across it.
double rim_distance(const Vec3& p, Vec3* across) {
  const double u = std::atan2(p.y(), p.x()), arc = u, z = p.z();
  const double a2 = std::remainder(arc - kPi, 2 * kPi);
  const double d1 = std::hypot(arc, z), d2 = std::hypot(a2, z);
  const Vec3 tu(-std::sin(u), std::cos(u), 0), ez(0, 0, 1);
  if (std::abs(d1 - kR1) < std::abs(d2 - kR2)) {
    if (across && d1 > 0) *across = (arc / d1) * tu + (z / d1) * ez;
    return std::abs(d1 - kR1);
  }
  if (across && d2 > 0) *across = (a2 / d2) * tu + (z / d2) * ez;
  return std::abs(d2 - kR2);
}

std::string thousands(long n) {
  std::string s = std::to_string(n);
  for (int i = int(s.size()) - 3; i > 0; i -= 3) s.insert(size_t(i), ",");
  return s;
}

double line_angle_deg(const Vec3& a, const Vec3& b) {
  return std::acos(std::min(1.0, std::abs(a.normalized().dot(b.normalized())))) * 180 / kPi;
}

}  // namespace

int main(int argc, char** argv) {
  const rkbench::Args args = rkbench::parse_args(argc, argv, {1000000});
  std::printf("threads: %d\n", omp_get_max_threads());
  for (long size : args.sizes) {
    rktest::ReliefShape s;
    s.noise = 0.1;
    const rktest::Relief r = rktest::discs_on_cylinder_of_size(size, s);
    const int nf = r.mesh.n_faces();
    const double band = 2 * s.width;
    for (int rep = 0; rep < args.repeat; ++rep) {
      // ---- Field ----
      rkbench::PeakMemory mem;
      mem.start();
      ProminentFieldParams fp;
      fp.progress = rkbench::stage_progress;
      rkbench::g_stages.start();
      double t0 = rkbench::now();
      const ProminentFieldResult f = compute_prominent_field(r.mesh, fp);
      const double total = rkbench::now() - t0;
      std::vector<double> err;
      for (int v = 0; v < r.mesh.n_vertices(); ++v) {
        Vec3 across;
        const Vec3& p = r.mesh.vertices[v];
        if (std::abs(p.z()) > 0.9 || rim_distance(p, &across) > band) continue;
        const Vec3& n = f.curvature->normal[v];
        err.push_back(line_angle_deg(f.field[v], across - n * n.dot(across)));
      }
      std::printf("| %s | prominent field: whole filter | %.2f s | %.2f s | %.0f MiB | median angle %.2f deg |\n",
                  thousands(nf).c_str(), total, total * 1e6 / nf, mem.grown_mib(), rktest::median(err));
      std::printf("| %s | prominent field: field stage (system, solve, normalisation) | %.2f s | %.2f s | | %s |\n",
                  thousands(nf).c_str(), f.field_seconds, f.field_seconds * 1e6 / nf, f.solve.summary().c_str());
      std::printf("   stages:");
      for (const auto& [what, t] : rkbench::g_stages.time) std::printf(" %s %.2f s;", what.c_str(), t);
      std::printf("\n");
      const double t1 = rkbench::now();
      const ColoringResult col = curvature_coloring(*f.curvature, &f.field, f.scale.counts, ColoringCurvature::Prominent, 1);
      std::printf("| %s | prominent coloring after the field | %.3f s | | | lambda %.4g |\n", thousands(nf).c_str(),
                  rkbench::now() - t1, col.lambda);
    }
    // ---- Enhancement: eroded steps, 10 % noise; accuracy against sharp steps ----
    rktest::ReliefShape worn = s, sharp;
    worn.width = 0.04;
    sharp.width = 0.008;
    const rktest::Relief noisy = rktest::discs_on_cylinder_of_size(size, worn);
    const rktest::Relief clean = rktest::discs_on_cylinder_of_size(size, sharp);
    std::vector<int> near;
    for (int v = 0; v < noisy.mesh.n_vertices(); ++v)
      if (std::abs(noisy.mesh.vertices[v].z()) < 0.9 && rim_distance(noisy.mesh.vertices[v], nullptr) < band) near.push_back(v);
    auto rms_near = [&](const std::vector<Vec3>& pos) {
      std::vector<Vec3> pts;
      for (int v : near) pts.push_back(pos[v]);
      const std::vector<double> d = rktest::distance_to_surface(clean.mesh, pts, 2 * worn.height);
      double sum = 0;
      for (double x : d) sum += std::isfinite(x) ? x * x : 4 * worn.height * worn.height;
      return std::sqrt(sum / d.size()) / noisy.mean_edge;
    };
    for (int rep = 0; rep < args.repeat; ++rep) {
      rkbench::PeakMemory mem;
      mem.start();
      const double t0 = rkbench::now();
      const EnhanceResult e = enhance_relief(noisy.mesh);
      const double total = rkbench::now() - t0;
      std::printf("| %s | prominent enhancement, to the automatic stop | %.2f s | %.2f s | %.0f MiB | RMS near the rims "
                  "%.3f -> %.3f (step 1: %.3f) edge lengths |\n",
                  thousands(nf).c_str(), total, total * 1e6 / nf, mem.grown_mib(), rms_near(noisy.mesh.vertices),
                  rms_near(e.positions), rms_near(e.bilateral));
      std::printf("   field %.2f s (of which field stage %.2f s), bilateral %.2f s (%d passes), flow %.2f s for %d "
                  "iterations = %.3f s per iteration (%s)\n",
                  total - e.bilateral_seconds - e.flow_seconds, e.field.field_seconds, e.bilateral_seconds,
                  EnhanceParams::kDefaultBilateralIterations, e.flow_seconds, e.flow_iterations,
                  e.flow_iterations ? e.flow_seconds / e.flow_iterations : 0.0,
                  e.converged ? "automatic stop reached" : "stopped at the limit");
    }
  }
  return 0;
}
