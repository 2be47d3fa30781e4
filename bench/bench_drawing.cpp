// Benchmark of relief reconstruction from line drawings (reliefkit/line_drawing.h,
// drawing_interpretation.h, drawing_relief.h): time, peak memory, and the accuracy of what was timed.
//   build/bench/bench_drawing [--sizes 2000000] [--repeat 1]
// 1. Curve extraction on the 2480 x 3425 real drawing ../shared/data/drawings/lithic_replica_1.png
//    (accuracy: curve count and length; the synthetic recall/precision is a unit test).
// 2. Reconstruction on the nested synthetic drawing scaled to ~`size` faces of the base grid
//    (cell 1.5 px): interpretation, the two solves of eqs. 7.4 / 7.6; accuracy = RMS error of the
//    free surface against the known levels after the global scale fit (in steps).
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
  {
    const std::string path = std::string(RELIEFKIT_SHARED_DATA) + "/drawings/lithic_replica_1.png";
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
      std::printf("extraction %dx%d: %.2f s, peak +%.0f MiB; %zu curves, %.0f px of curves, %lld line points, %zu junctions\n",
                  img.cols, img.rows, best, mem.grown_mib(), c.curves.size(), c.total_length(), c.line_points,
                  c.junctions.size());
    }
  }
  for (long size : args.sizes) {
    const double cell = 1.5;
    // 2 faces per cell: (600 s / cell)^2 * 2 = size.
    const double scale = std::sqrt(size / 2.0) * cell / 600;
    const cv::Mat img = rktest::nested_drawing(scale, std::max(2, int(std::lround(2 * scale / 2))));
    const DrawingCurves c = extract_drawing_curves(img);
    double t_interp = 1e300, t_relief = 1e300;
    DrawingRelief r;
    DrawingInterpretation d;
    TriMesh grid;
    mem.start();
    for (int rep = 0; rep < args.repeat; ++rep) {
      double t0 = rkbench::now();
      d = interpret_drawing(c);
      t_interp = std::min(t_interp, rkbench::now() - t0);
      t0 = rkbench::now();
      grid = drawing_grid(img.cols, img.rows, cell, 1.0);
      DrawingReliefParams p;
      r = reconstruct_drawing_relief(grid, c, d, p);
      t_relief = std::min(t_relief, rkbench::now() - t0);
    }
    const rktest::LevelFit fit = rktest::fit_levels(grid, 1.0, r, d, {int(5 * scale), int(5 * scale)});
    std::printf("reconstruction %dx%d px, %d faces (%d vertices): interpretation %.2f s, relief %.2f s, peak +%.0f MiB; "
                "%zu curves, %d regions; RMS %.3f step after the scale fit (%.3f per level); solves: %s | %s\n",
                img.cols, img.rows, grid.n_faces(), grid.n_vertices(), t_interp, t_relief, mem.grown_mib(), c.curves.size(),
                d.region_count, fit.rms_steps, fit.scale, r.laplacian_solve.summary().c_str(), r.relief_solve.summary().c_str());
  }
  return 0;
}
