// Benchmark of the base from a drawing's silhouettes (reliefkit/drawing/base_library.h, thesis sect. 7.5):
// time, peak memory, and the accuracy of what was timed.
//   build/bench/bench_bases [--sizes 100000] [--repeat 3]
// 1. Search: reading the shipped library (build/bases, features from its cache) and searching it
//    (324 models; and the same features repeated to 2,268 models, the thesis' "nearly 2000") for a
//    front view; accuracy = top-1 class over 45 held-out models drawn as figures (the search timed).
// 2. Deformation of a jug of ~`size` faces to the drawn outline of another jug: one pass (the
//    thesis' single solve) and the default passes; accuracy = the silhouette's Hausdorff distance
//    to the outline (% of its size) before and after, and the change of the Laplacian coordinates.
#include <cstdio>
#include <omp.h>

#include "bases.h"
#include "bench_util.h"
#include "reliefkit/drawing/line_drawing.h"

using namespace reliefkit;

namespace {
Outline drawn(const TriMesh& upright_model, std::mt19937& rng) {
  const cv::Mat img = rktest::draw_figure(mesh_outline(upright_model, ViewKind::Front, 600), {}, rng);
  Outline o = drawing_outlines(drawing_grey(img), cv::Rect(), 1).front().outline;
  for (auto& p : o) p.y() = -p.y();
  return o;
}
}  // namespace

int main(int argc, char** argv) {
  const rkbench::Args args = rkbench::parse_args(argc, argv, {100000});
  std::printf("threads: %d\n", omp_get_max_threads());
  rkbench::PeakMemory mem;
  BaseLibrary lib;
  double t0 = rkbench::now();
  add_library_folder(lib, RELIEFKIT_BASES_DIR);
  std::printf("library %s: %zu models read in %.3f s (%s)\n", RELIEFKIT_BASES_DIR, lib.models.size(), rkbench::now() - t0,
              lib.notes.empty() ? "features from the cache" : lib.notes.front().c_str());
  if (lib.models.empty()) return 1;
  // Held-out drawings (another seed), front view, turned up to 20 degrees, either way round.
  std::mt19937 rng(11);
  std::vector<std::pair<std::string, SilhouetteFeature>> queries;
  for (const auto& s : standard_base_specs(5, 4242)) {
    std::uniform_real_distribution<double> yaw(-20, 20);
    const TriMesh m = rktest::upright(make_base_model(s), yaw(rng), rng() % 2);
    queries.push_back({base_class_name(s.kind), circle_feature(drawn(m, rng))});
  }
  BaseLibrary big = lib;
  while (big.models.size() < 2000) big.models.insert(big.models.end(), lib.models.begin(), lib.models.end());
  for (const BaseLibrary* l : {&lib, &big}) {
    double best = 1e300;
    int right = 0;
    for (int rep = 0; rep < args.repeat; ++rep) {
      right = 0;
      double total = 0;
      for (const auto& [kind, f] : queries) {
        const double t = rkbench::now();
        const auto m = retrieve_bases(*l, {{ViewKind::Front, f}}, 5);
        total += rkbench::now() - t;
        right += l->models[size_t(m[0].model)].kind == kind;
      }
      best = std::min(best, total / queries.size());
    }
    std::printf("search of %zu models (48 orientations each): %.4f s per drawing; top-1 class %d / %zu\n", l->models.size(),
                best, right, queries.size());
  }
  // Deformation of a fine model.
  for (long size : args.sizes) {
    BaseModelSpec spec = standard_base_specs(1)[4];  // a jug
    int around = 96;
    TriMesh model = make_base_model(spec, around);
    while (model.n_faces() < 0.9 * size) {
      around = int(around * std::sqrt(double(size) / model.n_faces())) + 1;
      model = make_base_model(spec, around);
    }
    model = rktest::upright(model);
    const Outline target = drawn(rktest::upright(make_base_model(standard_base_specs(2, 99)[9])), rng);
    const std::vector<ViewOutline> views = {{ViewKind::Front, target}};
    const TriMesh placed = place_on_outlines(model, views);
    for (int passes : {1, DeformParams{}.passes}) {
      DeformParams p;
      p.passes = passes;
      p.progress = rkbench::stage_progress;
      DeformReport rep;
      double best = 1e300;
      mem.start();
      std::string stages;
      for (int r = 0; r < args.repeat; ++r) {
        rkbench::g_stages.start();
        const double t = rkbench::now();
        deform_to_outlines(placed, views, p, &rep);
        best = std::min(best, rkbench::now() - t);
        rkbench::g_stages.report("end");
        stages.clear();
        for (const auto& [what, sec] : rkbench::g_stages.time) stages += "  " + what + " " + std::to_string(sec).substr(0, 5) + " s";
      }
      std::printf("deformation, %d faces, %s: %.2f s (%d pass%s), peak +%.0f MiB; silhouette off the outline %.2f %% -> %.2f %%, "
                  "Laplacian coordinates changed %.1f %%\n",
                  model.n_faces(), passes == 1 ? "one solve (thesis)" : "default", best, rep.passes, rep.passes > 1 ? "es" : "",
                  mem.grown_mib(), 100 * rep.hausdorff_before, 100 * rep.hausdorff_after, 100 * rep.laplacian_change);
      std::printf("  stages:%s\n", stages.c_str());
    }
  }
  return 0;
}
