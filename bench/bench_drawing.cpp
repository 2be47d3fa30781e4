// Benchmark of relief reconstruction from line drawings (reliefkit/drawing/line_drawing.h,
// drawing_interpretation.h, drawing_relief.h): time, peak memory, and the accuracy of what was timed.
//   build/bench/bench_drawing [--sizes 2000000] [--repeat 1]
// 1. Curve extraction on the 2480 x 3425 real drawing ../shared/data/drawings/lithic_replica_1.png
//    (accuracy: curve count and length; the synthetic recall/precision is a unit test).
// 2. Reconstruction with ~`size` faces: the nested synthetic drawing scaled up (cell 1.5 px), and
//    the real drawing's extent (cell chosen for the size): the two solves of eqs. 7.4 / 7.6 by
//    conjugate gradients started from the interpretation's levels (the default) and by CHOLMOD, in
//    one run; accuracy = RMS error of the free surface against the levels after the global scale
//    fit (in steps), and the largest difference between the two solvers' reliefs.
#include <cmath>
#include <cstdio>
#include <opencv2/imgcodecs.hpp>
#include <omp.h>

#include "bench_util.h"
#include "drawings.h"

using namespace reliefkit;

int main(int argc, char** argv) {
  const rkbench::Args args = rkbench::parse_args(argc, argv, {2000000});
  std::printf("threads: %d\n", omp_get_max_threads());
  rkbench::PeakMemory mem;
  DrawingCurves real;
  {
    const std::string path = std::string(RELIEFKIT_DRAWINGS) + "/lithic_replica_1.png";
    const cv::Mat img = cv::imread(path, cv::IMREAD_UNCHANGED);
    if (img.empty()) {
      std::printf("extraction: %s not readable, skipped\n", path.c_str());
    } else {
      double best = 1e300;
      DrawingCurves c;
      mem.start();
      for (int rep = 0; rep < args.repeat; ++rep) {
        const double t0 = rkbench::now();
        c = extract_drawing_curves(img);
        best = std::min(best, rkbench::now() - t0);
      }
      real = c;
      std::printf("extraction %dx%d: %.2f s, peak +%.0f MiB; %zu curves, %.0f px of curves, %lld line points, %zu junctions\n",
                  img.cols, img.rows, best, mem.grown_mib(), c.curves.size(), c.total_length(), c.line_points,
                  c.junctions.size());
    }
  }
  // Reconstruction: the thesis' speed-up (conjugate gradients from the levels) against CHOLMOD.
  auto reconstruct = [&](const char* what, const DrawingCurves& c, int x0, int y0, int w, int h, double cell, cv::Point paper) {
    const DrawingInterpretation d = interpret_drawing(c);
    const TriMesh grid = drawing_grid(w, h, cell, 1.0, x0, y0);
    double t[2] = {1e300, 1e300};
    DrawingRelief r[2];
    double peak[2] = {0, 0};
    for (int m = 0; m < 2; ++m) {
      DrawingReliefParams p;
      p.step_height = 10;
      p.solver = m == 0 ? SolverMethod::Auto : SolverMethod::Direct;
      for (int rep = 0; rep < args.repeat; ++rep) {
        mem.start();
        const double t0 = rkbench::now();
        r[m] = reconstruct_drawing_relief(grid, c, d, p);
        t[m] = std::min(t[m], rkbench::now() - t0);
        peak[m] = std::max(peak[m], mem.grown_mib());
      }
    }
    const rktest::LevelFit fa = rktest::fit_levels(grid, 1.0, r[0], d, paper), fb = rktest::fit_levels(grid, 1.0, r[1], d, paper);
    double diff = 0;
    for (size_t v = 0; v < r[0].height.size(); ++v) diff = std::max(diff, std::abs(r[0].height[v] - r[1].height[v]));
    std::printf("%s: %d faces (%d vertices, cell %.2g px), %zu curves, %d regions\n"
                "  CG from the levels: %.2f s, peak +%.0f MiB, RMS %.3f step after the scale fit (%.3f per level); %s | %s\n"
                "  CHOLMOD:            %.2f s, peak +%.0f MiB, RMS %.3f step (%.3f per level); largest difference %.1e step\n"
                "  speed-up %.2fx\n",
                what, grid.n_faces(), grid.n_vertices(), cell, c.curves.size(), d.region_count, t[0], peak[0], fa.rms_steps,
                fa.scale / 10, r[0].laplacian_solve.summary().c_str(), r[0].relief_solve.summary().c_str(), t[1], peak[1],
                fb.rms_steps, fb.scale / 10, diff / 10, t[1] / t[0]);
  };
  for (long size : args.sizes) {
    const double cell = 1.5;
    // 2 faces per cell: (600 s / cell)^2 * 2 = size.
    const double scale = std::sqrt(size / 2.0) * cell / 600;
    const cv::Mat img = rktest::nested_drawing(scale, std::max(2, int(std::lround(scale))));
    reconstruct("reconstruction, nested drawing", extract_drawing_curves(img), 0, 0, img.cols, img.rows, cell,
                {int(5 * scale), int(5 * scale)});
    if (!real.curves.empty()) {
      const cv::Rect a = drawing_extent(real, 20);
      const double c2 = std::sqrt(2.0 * a.width * a.height / size);
      reconstruct("reconstruction, lithic_replica_1", real, a.x, a.y, a.width, a.height, c2, {a.x + 2, a.y + 2});
    }
  }
  return 0;
}
