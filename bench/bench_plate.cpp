// Benchmark of the illustration plate (reliefkit/illustration/plate.h): time per stage, peak
// memory, and the accuracy of what was timed.
//   build/bench/bench_plate [--sizes 1000000,4000000] [--repeat 3]
// A disc of radius 0.5 raised on the plane [-1, 1]^2, the mesh unit 50 mm, drawn 1:1 from above
// at 300 dpi with a vertical section through the middle, on a regular grid and on a jittered
// (irregular) one of about `size` faces. The curve is the step's true mid-height line (a circle
// of 25 mm on the page). Accuracy: the farthest drawn point from that circle, and the farthest
// profile point from the profile's true height (both in mm on the page). Then the shared coin
// scan (../shared/data), with the same disc's circle scaled to it: time only.
#include <omp.h>

#include <cmath>
#include <cstdio>

#include "bench_util.h"
#include "reliefkit/illustration/plate.h"
#include "reliefs.h"

using namespace reliefkit;

namespace {

PlateCurves boundary_curve(const std::vector<Vec3>& boundary, double scale) {
  PlateCurves c;
  c.name = "boundary";
  for (const auto& p : boundary) c.points.push_back(scale * p);
  for (size_t k = 0; k < c.points.size(); ++k) c.segments.push_back({int(k), int((k + 1) % c.points.size())});
  return c;
}

// The farthest drawn point of the boundary layer from the 25 mm circle, and of the section's
// profile from the relief's height along x = 0 (mm on the page).
std::pair<double, double> page_errors(const Plate& p, const rktest::ReliefShape& shape) {
  const double mm = 50;  // per mesh unit, at 1:1
  const Vec2 centre = p.drawing_origin_mm + 0.5 * p.drawing_size_mm;
  double curve = 0, profile = 0, front = 1e300;
  for (const auto& path : p.paths)
    if (path.layer == "section")
      for (const auto& q : path.points) front = std::min(front, q.x());
  for (const auto& path : p.paths)
    for (const auto& q : path.points) {
      if (path.layer == "boundary") curve = std::max(curve, std::abs((q - centre).norm() - 0.5 * mm));
      if (path.layer != "section") continue;
      const double y = 1 - (q.y() - p.drawing_origin_mm.y()) / mm;  // mesh units
      const double height = shape.height * 0.5 * (1 + std::tanh((0.5 - std::abs(y)) / shape.width));
      profile = std::max(profile, std::abs((shape.height - height) * mm - (q.x() - front)));
    }
  return {curve, profile};
}

void time_plate(const char* name, const TriMesh& mesh, const PlateCurves& curve, const PlateParams& params, int repeat,
                rkbench::PeakMemory& mem, const rktest::ReliefShape* shape) {
  double best = 1e300, svg_time = 0;
  Plate plate;
  std::string stages;
  mem.start();
  for (int r = 0; r < repeat; ++r) {
    rkbench::g_stages.start();
    const double t = rkbench::now();
    plate = make_plate(mesh, {}, {curve}, PlateView{}, params);
    best = std::min(best, rkbench::now() - t);
    rkbench::g_stages.report("end");
    stages.clear();
    for (const auto& [what, sec] : rkbench::g_stages.time) stages += "  " + what + " " + std::to_string(sec).substr(0, 5) + " s";
  }
  const double t = rkbench::now();
  const size_t bytes = plate_svg(plate).size();
  svg_time = rkbench::now() - t;
  std::printf("%s, %d faces: plate %.3f s, SVG %.3f s (%.1f MB), peak +%.0f MiB; %zu paths, %ld segments visible, %ld section "
              "segments",
              name, mesh.n_faces(), best, svg_time, bytes / 1e6, mem.grown_mib(), plate.paths.size(), plate.visible_segments,
              plate.section_segments);
  if (shape) {
    const auto [curve_err, profile_err] = page_errors(plate, *shape);
    std::printf("; the curve within %.3f mm of its circle, the profile within %.3f mm of its height (a pixel: %.3f mm)",
                curve_err, profile_err, 25.4 / params.dpi);
  }
  std::printf("\n  stages:%s\n", stages.c_str());
}
}  // namespace

int main(int argc, char** argv) {
  const rkbench::Args args = rkbench::parse_args(argc, argv, {1000000, 4000000});
  std::printf("threads: %d\n", omp_get_max_threads());
  rkbench::PeakMemory mem;
  PlateParams params;
  params.unit_mm = 50;
  params.ratio = 1;
  params.section.axis = SectionAxis::vertical;
  params.progress = rkbench::stage_progress;
  for (long size : args.sizes) {
    const int n = int(std::lround(std::sqrt(size / 2.0)));
    for (double jitter : {0.0, 0.3}) {
      rktest::ReliefShape shape;
      shape.jitter = jitter;
      const rktest::Relief r = rktest::disc_on_plane(shape, n);
      time_plate(jitter > 0 ? "disc on a plane, irregular" : "disc on a plane, regular", r.mesh, boundary_curve(r.boundary, 1),
                 params, args.repeat, mem, &shape);
    }
  }
  TriMesh coin;
  if (rkbench::read_scan(RELIEFKIT_SHARED_DATA "/meshes/penny_gigamacro.ply", coin)) {
    params.unit_mm = 0.0099;  // 19.05 mm across 1,924 units
    params.ratio = 0;
    Vec3 lo = coin.vertices[0], hi = lo;
    for (const auto& v : coin.vertices) lo = lo.cwiseMin(v), hi = hi.cwiseMax(v);
    PlateCurves circle = boundary_curve(rktest::disc_on_plane({}, 20).boundary, 0.5 * (hi - lo).x());
    for (auto& p : circle.points) p += 0.5 * (lo + hi) + Vec3(0, 0, 0.5 * (hi - lo).z());
    time_plate("coin scan (penny_gigamacro.ply, irregular)", coin, circle, params, args.repeat, mem, nullptr);
  }
  return 0;
}
