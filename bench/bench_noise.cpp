// The noise estimate and the automatic pre-smoothing it drives.
//   build/bench/bench_noise              how the estimate tracks the true noise (0-20 % of the edge)
//   build/bench/bench_noise --sweep 100000,1000000
//        demarcating curves on the noisy cylinder relief at each size, for a range of fixed
//        pre-smoothing scales and for "auto": recall / precision / time (the measurements behind
//        automatic_presmoothing, docs/parameters.md)
#include <omp.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>

#include "bench_util.h"
#include "reliefkit/demarcating/demarcating.h"
#include "reliefkit/base/scale.h"
#include "mesh_files.h"
#include "reliefs.h"
#include "shapes.h"

using namespace reliefkit;

namespace {

rktest::Relief cylinder_relief(long faces, double noise) {
  rktest::ReliefShape shape;
  shape.noise = noise;
  return rktest::discs_on_cylinder_of_size(faces, shape);
}

void tracking() {
  std::printf("Noise estimate vs true noise (both relative to the median edge length)\n");
  std::printf("%-20s %8s %10s %10s %8s %14s\n", "surface", "faces", "true", "estimate", "ratio", "auto smooth/edge");
  const double levels[] = {0, 0.025, 0.05, 0.1, 0.15, 0.2};
  for (int shape = 0; shape < 4; ++shape)
    for (double lv : levels) {
      rktest::ReliefShape s;
      s.noise = lv;
      rktest::Relief r;
      const char* name = "";
      if (shape == 0) r = rktest::disc_on_plane(s), name = "disc on plane";
      if (shape == 1) r = rktest::disc_on_sphere(s), name = "disc on sphere";
      if (shape == 2) r = rktest::discs_on_cylinder(s), name = "discs on cylinder";
      if (shape == 3) {
        name = "jittered torus";
        r.mesh = rktest::torus(3, 1, 400, 160, 0.3, 1);
        r.mean_edge = edge_length_stats(r.mesh).mean;
        rktest::Rng rng(5);
        VertexFaces vf = vertex_faces(r.mesh);
        std::vector<Vec3> n = vertex_normals(r.mesh, vf);
        for (size_t i = 0; i < n.size(); ++i) r.mesh.vertices[i] += n[i] * (lv * r.mean_edge * rng.normal());
      }
      MeshScale sc = mesh_scale(r.mesh);
      NoiseEstimate e = estimate_noise(r.mesh, sc);
      const double truth = lv * r.mean_edge / sc.edge;
      std::printf("%-20s %8d %10.4f %10.4f %8s %14.2f\n", name, r.mesh.n_faces(), truth, e.relative,
                  truth > 0 ? std::to_string(e.relative / truth).substr(0, 5).c_str() : "-",
                  automatic_presmoothing(e, sc) / sc.edge);
    }
}

void sweep(const std::vector<long>& sizes) {
  std::printf("Demarcating curves on the cylinder relief, 10 %% noise, %d threads\n", omp_get_max_threads());
  std::printf("%-9s %-10s %8s %8s %9s %8s\n", "faces", "presmooth", "edges", "recall", "precision", "time s");
  const double fixed[] = {-1, 0.5, 1, 1.5, 2, 3, 4, 6, 8};
  for (long target : sizes) {
    rktest::Relief r = cylinder_relief(target, 0.1);
    MeshScale sc = mesh_scale(r.mesh);
    for (double s : fixed) {
      DemarcatingParams p;
      p.presmoothing = s < 0 ? Length::automatic() : Length::in_edges(s);
      double t0 = rkbench::now();
      DemarcatingResult res = compute_demarcating(r.mesh, p);
      double t = rkbench::now() - t0;
      rktest::Detection d = rktest::score(r, res.curves, r.mean_edge);
      rktest::Detection d3 = rktest::score(r, res.curves, 3 * r.mean_edge);
      double blen = 0, tot = 0;
      for (const auto& sg : res.curves.segments) {
        double l = (res.curves.points[sg[0]] - res.curves.points[sg[1]]).norm();
        tot += l;
        if (std::abs(res.curves.points[sg[0]].z()) > 0.85) blen += l;
      }
      blen = tot > 0 ? tot / std::max(blen, 1e-12) : 0;
      std::printf("%-9d %-10s %8.2f %8.3f %9.3f %8.2f  p3 %.3f total/rim %.2f thr %.3g med %.3g\n", r.mesh.n_faces(), s < 0 ? "auto" : "fixed",
                  res.presmoothing / sc.edge, d.recall, d.precision, t, d3.precision, 1.0 / blen, res.threshold, res.median_strength);
      std::fflush(stdout);
    }
  }
}

}  // namespace

int main(int argc, char** argv) {
  if (argc > 2 && !std::strcmp(argv[1], "--sweep")) {
    std::vector<long> sizes;
    for (const char* t = argv[2]; *t;) {
      char* end = nullptr;
      sizes.push_back(std::strtol(t, &end, 10));
      t = *end == ',' ? end + 1 : end;
    }
    sweep(sizes);
    return 0;
  }
  tracking();
  std::printf("\nReal scans (../shared/data/meshes)\n%-24s %8s %12s %10s %14s\n", "scan", "faces", "edge", "noise/edge",
              "auto smooth/edge");
  for (const char* name : {"penny_gigamacro.ply", "fertility.obj", "stanford-bunny.obj"}) {
    const std::string path = std::string(RELIEFKIT_SHARED_DATA) + "/meshes/" + name;
    try {
      TriMesh m = rktest::read_mesh(path).mesh;
      MeshScale sc = mesh_scale(m);
      NoiseEstimate e = estimate_noise(m, sc);
      std::printf("%-24s %8d %12.4g %10.4f %14.2f\n", name, m.n_faces(), sc.edge, e.relative,
                  automatic_presmoothing(e, sc) / sc.edge);
    } catch (const std::exception& ex) {
      std::printf("%-24s not read (%s)\n", name, ex.what());
    }
  }
  return 0;
}
