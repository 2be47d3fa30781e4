// Benchmark of the multi-scale curves (reliefkit/multiscale/multiscale.h): the whole Multi-scale Ridges and
// Valleys and Multi-scale Relief Edges computations on ~1 M faces, time and peak memory, each
// with the accuracy of what it timed (recall / precision against the known lines), and the
// single-scale detectors on the same meshes for comparison.
//   build/bench/bench_multiscale [--sizes 1000000] [--repeat 1]
// Ridges & valleys: the unit test's noisy cylinder (20 % noise; valleys and ridges 0.35 and 5
// edge lengths wide), made longer to reach the size. Relief edges: (a) the noisy disc reliefs of
// the relief-edge benchmarks (15 % noise); (b) the hard case at the unit test's size
// (tests/unit/multiscale/test_multiscale.cpp): a sharp narrow band and a wide soft band on a noisy cylinder.
#include <cmath>
#include <cstdio>
#include <omp.h>

#include "bench_util.h"
#include "reliefkit/multiscale/multiscale.h"
#include "reliefs.h"

using namespace reliefkit;
using rktest::AxialFeature;

namespace {

constexpr int kAround = 1800;
constexpr double kTolerance = 0.005;

double f1(double r, double p) { return r + p > 0 ? 2 * r * p / (r + p) : 0; }

// Mean recall and length-weighted precision over the given curve layers and kinds.
std::pair<double, double> score(const rktest::AxialCylinder& c, const std::vector<const Polylines*>& layers,
                                const std::vector<AxialFeature::Kind>& kinds) {
  double recall = 0, good = 0, total = 0;
  int n = 0;
  for (size_t l = 0; l < layers.size(); ++l) {
    const auto s = rktest::score_axial(c, *layers[l], {kinds[l]}, kTolerance, 3 * c.edge);
    for (size_t i = 0; i < c.features.size(); ++i)
      if (c.features[i].kind == kinds[l]) recall += s.recall[i], ++n;
    good += s.precision * s.length, total += s.length;
  }
  return {n ? recall / n : 0, total > 0 ? good / total : 0};
}

}  // namespace

int main(int argc, char** argv) {
  const auto args = rkbench::parse_args(argc, argv, {1000000});
  std::printf("Multi-scale curves, %d threads (time s, per M faces, peak MiB above the mesh, recall / precision)\n",
              omp_get_max_threads());
  for (long faces : args.sizes) {
    const double h = 2 * M_PI / kAround;
    const double length = faces / (2.0 * kAround) * h;
    std::vector<AxialFeature> rv;
    for (int k = 0; k < 12; ++k)
      rv.push_back({k % 4 < 2 ? AxialFeature::Valley : AxialFeature::Ridge, (k * 150 + 0.37 * k) * h,
                    k % 2 == 0 ? 0.35 * h : 5 * h, 2 * h, 0, k % 2});
    const rktest::AxialCylinder cyl = rktest::axial_cylinder(rv, kAround, length, 0.2);
    for (int rep = 0; rep < args.repeat; ++rep) {
      rkbench::PeakMemory mem;
      mem.start();
      const double t0 = rkbench::now();
      const MultiscaleRidgeValleys ms = multiscale_ridges_valleys(cyl.mesh, {});
      const double t = rkbench::now() - t0;
      const auto [r, p] = score(cyl, {&ms.curves.ridges, &ms.curves.valleys}, {AxialFeature::Ridge, AxialFeature::Valley});
      std::printf("%9d faces  multi-scale ridges & valleys  %7.2f s  %6.2f s/M  %6.0f MiB  %.3f / %.3f (F1 %.3f)\n",
                  cyl.mesh.n_faces(), t, t * 1e6 / cyl.mesh.n_faces(), mem.grown_mib(), r, p, f1(r, p));
      mem.start();
      const double t1 = rkbench::now();
      RidgeValleyParams sp;
      sp.presmoothing = Length::in_edges(2);
      const RidgeValleyResult ss = compute_ridges_valleys(cyl.mesh, sp);
      const double ts = rkbench::now() - t1;
      const auto [r1, p1] = score(cyl, {&ss.ridges, &ss.valleys}, {AxialFeature::Ridge, AxialFeature::Valley});
      std::printf("%9d faces  single scale (2 edge lengths)  %7.2f s  %6.2f s/M  %6.0f MiB  %.3f / %.3f (F1 %.3f)\n",
                  cyl.mesh.n_faces(), ts, ts * 1e6 / cyl.mesh.n_faces(), mem.grown_mib(), r1, p1, f1(r1, p1));
    }
    rktest::ReliefShape shape;
    shape.noise = 0.15;
    const rktest::Relief discs = rktest::discs_on_cylinder_of_size(faces, shape);
    for (int rep = 0; rep < args.repeat; ++rep) {
      rkbench::PeakMemory mem;
      mem.start();
      const double t0 = rkbench::now();
      const MultiscaleReliefEdges ms = multiscale_relief_edges(discs.mesh, {});
      const double t = rkbench::now() - t0;
      const rktest::Detection d = rktest::score(discs, ms.curves.edges, 2 * discs.mean_edge);
      std::printf("%9d faces  multi-scale relief edges (discs) %5.2f s  %6.2f s/M  %6.0f MiB  %.3f / %.3f\n",
                  discs.mesh.n_faces(), t, t * 1e6 / discs.mesh.n_faces(), mem.grown_mib(), d.recall, d.precision);
    }
  }
  // The hard relief-edge case at the unit tests' size (260 K faces).
  const double h = 2 * M_PI / kAround;
  std::vector<AxialFeature> bands;
  for (int k = 0; k < 6; ++k)
    bands.push_back({AxialFeature::Band, (k * 300 + 0.37 * k) * h, k % 2 == 0 ? 0.3 * h : 8 * h,
                     k % 2 == 0 ? 1.5 * h : 4 * h, k % 2 == 0 ? 2.5 * h : 60 * h, k % 2});
  const rktest::AxialCylinder bc = rktest::axial_cylinder(bands, kAround, 0.25, 0.2);
  auto band_score = [&](const char* name, const Polylines& e) {
    const auto s = rktest::score_axial(bc, e, {AxialFeature::Band}, kTolerance, 3 * bc.edge);
    double sharp = 0, soft = 0;
    for (size_t i = 0; i < bands.size(); ++i) (bands[i].group ? soft : sharp) += s.recall[i] / 3;
    std::printf("  narrow band (1.5 high, 2.5 wide) + soft band (4 high, tanh 8), 20 %% noise: %-26s recall narrow %.3f soft %.3f, "
                "precision %.3f, F1 %.3f\n",
                name, sharp, soft, s.precision, f1(0.5 * (sharp + soft), s.precision));
  };
  band_score("multi-scale", multiscale_relief_edges(bc.mesh, {}).curves.edges);
  for (double s : {1.0, 1.5, 2.0, 3.0, 4.0}) {
    ReliefEdgeParams p;
    p.presmoothing = Length::in_edges(s);
    char name[40];
    std::snprintf(name, sizeof name, "single, %.1f edge lengths", s);
    band_score(name, compute_relief_edges(bc.mesh, p).edges);
  }
}
