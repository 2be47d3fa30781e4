// Benchmark of the multi-scale curves (reliefkit/multiscale/multiscale.h): the whole Multi-scale Ridges and
// Valleys and Multi-scale Relief Edges computations on ~1 M faces, time and peak memory, each
// with the accuracy of what it timed (recall / precision against the known lines), and the
// single-scale detectors on the same meshes for comparison.
//   build/bench/bench_multiscale [--sizes 1000000] [--repeat 1]
//   build/bench/bench_multiscale --family   (issue 40 point 2: the width-ratio family, below)
//   build/bench/bench_multiscale --family-single-reach   (what any single scale reaches on it)
// Ridges & valleys: the unit test's noisy cylinder (20 % noise; valleys and ridges 0.35 and 5
// edge lengths wide), made longer to reach the size. Relief edges: (a) the noisy disc reliefs of
// the relief-edge benchmarks (15 % noise); (b) the hard case at the unit test's size
// (tests/unit/multiscale/test_multiscale.cpp): a sharp narrow band and a wide soft band on a noisy cylinder.
#include <cmath>
#include <cstdio>
#include <cstring>
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

// Issue 40 point 2 (issue 22's family, its bars restated): multi-scale ridges and valleys
// against the best of five single scales and the single scale at its defaults (automatic
// pre-smoothing) on the unit test's noisy cylinder (260 K faces, 20 % noise), over fine widths,
// width ratios and depths. The bars: recall >= 0.9 on fine and coarse and precision >= 0.8 in at
// least 20 of the 24; F1 >= best single - 0.02 in all 24; mean F1 >= the defaults' + 0.05.
void width_ratio_family() {
  std::printf("Width-ratio family (20 %% noise; widths and depths in edge lengths; best single of 0, 1, 2, 4, 8)\n");
  int met = 0, within = 0, n = 0;
  double sum_multi = 0, sum_default = 0, sum_best = 0;
  for (double fine : {0.35, 1.0})
    for (double ratio : {3.0, 6.0, 14.0, 30.0})
      for (double depth : {1.0, 2.0, 4.0}) {
        const rktest::AxialCylinder cyl =
            rktest::axial_cylinder(rktest::fine_and_coarse_lines(kAround, fine, fine * ratio, depth), kAround, 0.25, 0.2);
        auto scored = [&](const RidgeValleyResult& r) {
          return score_fine_coarse(cyl, r.ridges, r.valleys, kTolerance, 3 * cyl.edge);
        };
        const double t0 = rkbench::now();
        const MultiscaleRidgeValleys ms = multiscale_ridges_valleys(cyl.mesh, {});
        const double t = rkbench::now() - t0;
        const rktest::FineCoarseScore m = scored(ms.curves);
        const rktest::FineCoarseScore at_defaults = scored(compute_ridges_valleys(cyl.mesh, {}));
        rktest::FineCoarseScore best;
        double best_at = 0;
        for (double s : {0.0, 1.0, 2.0, 4.0, 8.0}) {
          RidgeValleyParams p;
          p.presmoothing = Length::in_edges(s);
          const rktest::FineCoarseScore x = scored(compute_ridges_valleys(cyl.mesh, p));
          if (x.f1() > best.f1()) best = x, best_at = s;
        }
        const bool bar = m.fine >= 0.9 && m.coarse >= 0.9 && m.precision >= 0.8;
        met += bar, within += m.f1() >= best.f1() - 0.02, ++n;
        sum_multi += m.f1(), sum_default += at_defaults.f1(), sum_best += best.f1();
        std::printf("fine %.2f ratio %2.0f depth %.0f  multi %.3f / %.3f / %.3f F1 %.3f (%4.1f s)  "
                    "single %.0f: %.3f / %.3f / %.3f F1 %.3f  defaults F1 %.3f  %s\n",
                    fine, ratio, depth, m.fine, m.coarse, m.precision, m.f1(), t, best_at, best.fine, best.coarse,
                    best.precision, best.f1(), at_defaults.f1(), bar ? "bar met" : "");
        std::fflush(stdout);
      }
  std::printf("recall >= 0.9 on both and precision >= 0.8: %d of %d (bar: 20); F1 >= best single - 0.02: %d of %d "
              "(bar: all)\nmean F1: multi %.3f, best single %.3f, single at defaults %.3f (bar: multi >= defaults + 0.05)\n",
              met, n, within, n, sum_multi / n, sum_best / n, sum_default / n);
}

// What the family's bar asks of the multi-scale reading, set against what a single scale can
// reach: per configuration, the highest fine and coarse recall of the single scales from 0 to 16
// edge lengths (each with the scale reaching it and its precision). Where no scale reaches recall
// 0.9 on a kind of line, the multi-scale reading would have to find lines no smoothing of this
// mesh shows as ridges or valleys.
void family_single_reach() {
  std::printf("Width-ratio family: the best fine and coarse recall of single scales 0-16 edge lengths\n"
              "(recall at that scale, the scale, its precision)\n");
  int reachable = 0, n = 0;
  for (double fine : {0.35, 1.0})
    for (double ratio : {3.0, 6.0, 14.0, 30.0})
      for (double depth : {1.0, 2.0, 4.0}) {
        const rktest::AxialCylinder cyl =
            rktest::axial_cylinder(rktest::fine_and_coarse_lines(kAround, fine, fine * ratio, depth), kAround, 0.25, 0.2);
        rktest::FineCoarseScore best_fine, best_coarse;
        double fine_at = 0, coarse_at = 0;
        for (double s : {0.0, 0.5, 1.0, 2.0, 4.0, 8.0, 12.0, 16.0}) {
          RidgeValleyParams p;
          p.presmoothing = Length::in_edges(s);
          const RidgeValleyResult r = compute_ridges_valleys(cyl.mesh, p);
          const rktest::FineCoarseScore x = score_fine_coarse(cyl, r.ridges, r.valleys, kTolerance, 3 * cyl.edge);
          if (x.fine > best_fine.fine) best_fine = x, fine_at = s;
          if (x.coarse > best_coarse.coarse) best_coarse = x, coarse_at = s;
        }
        const bool reach = best_fine.fine >= 0.9 && best_coarse.coarse >= 0.9;
        reachable += reach, ++n;
        std::printf("fine %.2f ratio %2.0f depth %.0f  fine %.3f (scale %4.1f, precision %.3f)  coarse %.3f (scale %4.1f, "
                    "precision %.3f)  %s\n",
                    fine, ratio, depth, best_fine.fine, fine_at, best_fine.precision, best_coarse.coarse, coarse_at,
                    best_coarse.precision, reach ? "" : "no single scale reaches 0.9 on both");
        std::fflush(stdout);
      }
  std::printf("configurations where some single scale reaches recall 0.9 on the fine lines and some on the coarse: "
              "%d of %d\n", reachable, n);
}

}  // namespace

int main(int argc, char** argv) {
  if (argc > 1 && !std::strcmp(argv[1], "--family")) {
    width_ratio_family();
    return 0;
  }
  if (argc > 1 && !std::strcmp(argv[1], "--family-single-reach")) {
    family_single_reach();
    return 0;
  }
  const auto args = rkbench::parse_args(argc, argv, {1000000});
  std::printf("Multi-scale curves, %d threads (time s, per M faces, peak MiB above the mesh, recall / precision)\n",
              omp_get_max_threads());
  for (long faces : args.sizes) {
    const double h = 2 * M_PI / kAround;
    const double length = faces / (2.0 * kAround) * h;
    const rktest::AxialCylinder cyl =
        rktest::axial_cylinder(rktest::fine_and_coarse_lines(kAround, 0.35, 5, 2), kAround, length, 0.2);
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
