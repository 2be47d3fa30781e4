// Benchmark of the base from a drawing's silhouettes (reliefkit/drawing/base_library.h, thesis sect. 7.5):
// time, peak memory, and the accuracy of what was timed.
//   build/bench/bench_bases [--sizes 100000] [--repeat 3]
// 1. Search: reading the shipped library (build/bases, features from its cache) and searching it
//    (324 models; and the same features repeated to 2,268 models, the thesis' "nearly 2000") for a
//    front view; accuracy = top-1 class over 45 held-out models drawn as figures (the search timed).
// 2. Deformation of a jug of ~`size` faces (regular) to the drawn outline of another jug, and of
//    the Stanford bunny scan of ../shared/data (69 K faces, irregular) to its own front outline
//    made 1.25 times wider: one pass (the thesis' single solve), the default passes on the model
//    itself, and the default passes (on a coarse copy of a model above 40 K faces); accuracy = the
//    silhouette's Hausdorff distance to the outline (% of its size) before and after, and the
//    change of the Laplacian coordinates.
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
// The model placed on the outlines and deformed: the thesis' single solve, the default passes on
// the model itself (no coarse copy) and the default passes (on a coarse copy above 40 K faces).
void time_deformations(const char* name, const TriMesh& model, const std::vector<ViewOutline>& views, int repeat,
                       rkbench::PeakMemory& mem) {
  const TriMesh placed = place_on_outlines(model, views);
  struct Mode { const char* what; int passes, coarse_faces; };
  const DeformParams defaults;
  for (const Mode m : {Mode{"one solve (thesis)", 1, 0}, Mode{"default passes on the model itself", defaults.passes, 0},
                       Mode{"default", defaults.passes, defaults.coarse_faces}}) {
    DeformParams p;
    p.passes = m.passes;
    p.coarse_faces = m.coarse_faces;
    p.progress = rkbench::stage_progress;
    DeformReport rep;
    double best = 1e300;
    mem.start();
    std::string stages;
    for (int r = 0; r < repeat; ++r) {
      rkbench::g_stages.start();
      const double t = rkbench::now();
      deform_to_outlines(placed, views, p, &rep);
      best = std::min(best, rkbench::now() - t);
      rkbench::g_stages.report("end");
      stages.clear();
      for (const auto& [what, sec] : rkbench::g_stages.time) stages += "  " + what + " " + std::to_string(sec).substr(0, 5) + " s";
    }
    const std::string copy = rep.coarse_faces ? ", coarse copy of " + std::to_string(rep.coarse_faces) + " faces" : "";
    std::printf("deformation, %s, %d faces, %s: %.2f s (%d pass%s%s), peak +%.0f MiB; silhouette off the outline %.2f %% -> "
                "%.2f %%, Laplacian coordinates changed %.1f %%\n",
                name, model.n_faces(), m.what, best, rep.passes, rep.passes > 1 ? "es" : "", copy.c_str(), mem.grown_mib(),
                100 * rep.hausdorff_before, 100 * rep.hausdorff_after, 100 * rep.laplacian_change);
    std::printf("  stages:%s\n", stages.c_str());
  }
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
  // Deformation of a fine model: a regular jug, then a real irregular scan.
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
    time_deformations("jug (regular)", model, {{ViewKind::Front, target}}, args.repeat, mem);
  }
  TriMesh bunny;
  if (rkbench::read_scan(std::string(RELIEFKIT_SOURCE_DIR) + "/../shared/data/meshes/stanford-bunny.obj", bunny)) {
    bunny = normalize_to_principal_axes(bunny);
    Outline wider = mesh_outline(bunny, ViewKind::Front, 1024);
    for (auto& p : wider) p.x() *= 1.25;
    time_deformations("bunny scan (irregular, 1,113 unreferenced vertices)", bunny, {{ViewKind::Front, wider}}, args.repeat, mem);
  }
  return 0;
}
