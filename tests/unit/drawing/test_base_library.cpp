// Base from the drawing's silhouettes (reliefkit/drawing/base_library.h, thesis sect. 7.5): outlines of
// drawn figures, the circle-distance feature and its symmetries, retrieval of held-out models'
// classes, deformation to outlines (Hausdorff within 1 % of the outline), the cylinder made a
// goblet (fig. 7.10), the model folder and its cache, bad input.
#include <gtest/gtest.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <opencv2/imgproc.hpp>

#include "bases.h"
#include "reliefkit/drawing/base_library.h"
#include "reliefkit/drawing/line_drawing.h"

using namespace reliefkit;
namespace fs = std::filesystem;

namespace {

// The standard library (36 models per class) held in memory, features computed as from files.
const BaseLibrary& memory_library() {
  static const BaseLibrary lib = [] {
    BaseLibrary l;
    const auto specs = standard_base_specs();
    l.models.resize(specs.size());
#pragma omp parallel for schedule(dynamic)
    for (long i = 0; i < long(specs.size()); ++i) {
      auto& m = l.models[size_t(i)];
      m.name = specs[size_t(i)].name;
      m.kind = base_class_name(specs[size_t(i)].kind);
      m.feature = model_features(normalize_to_principal_axes(make_base_model(specs[size_t(i)])));
    }
    return l;
  }();
  return lib;
}

// Outline of a drawn figure: drawn as an image, found again by drawing_outlines, in pixels.
Outline drawn_outline(const Outline& truth, std::mt19937& rng, const rktest::FigureStyle& style = {}) {
  const cv::Mat img = rktest::draw_figure(truth, style, rng);
  return drawing_outlines(drawing_grey(img), cv::Rect(), 1).front().outline;
}
Outline flip_y(Outline o) {  // image pixels (y down) -> view coordinates (y up)
  for (auto& p : o) p.y() = -p.y();
  return o;
}

}  // namespace

TEST(BaseLibrary, ViewListIsParsed) {
  auto v = parse_drawing_views("");
  ASSERT_EQ(v.size(), 1u);
  EXPECT_EQ(v[0].kind, ViewKind::Front);
  v = parse_drawing_views("Front; top = 10, 20, 300, 200 ; side = lamp side.png");
  ASSERT_EQ(v.size(), 3u);
  EXPECT_EQ(v[1].kind, ViewKind::Top);
  EXPECT_EQ(v[1].region, cv::Rect(10, 20, 300, 200));
  EXPECT_EQ(v[2].kind, ViewKind::Side);
  EXPECT_EQ(v[2].image, "lamp side.png");
  EXPECT_THROW(parse_drawing_views("back"), InputError);
  EXPECT_THROW(parse_drawing_views("front; front"), InputError);
  EXPECT_THROW(parse_drawing_views("front = 1 2 3"), InputError);
  EXPECT_THROW(parse_drawing_views("front = 0 0 -5 100"), InputError);
}

TEST(BaseLibrary, FeatureSymmetriesArePermutations) {
  // A lamp's silhouette has no symmetry: mirroring or transposing the outline must give the
  // permuted feature.
  const TriMesh lamp = normalize_to_principal_axes(make_base_model(standard_base_specs(3)[1]));
  const Outline o = mesh_outline(lamp, 1, 3, 400);
  const auto f = circle_feature(o);
  for (int t = 0; t < 8; ++t) {
    const bool tr = t & 1, fu = t & 2, fv = t & 4;
    Outline m = o;
    for (auto& p : m) {
      if (tr) p = Vec2(p.y(), p.x());
      if (fu) p.x() = -p.x();
      if (fv) p.y() = -p.y();
    }
    const auto g = circle_feature(m), h = transform_feature(f, tr, fu, fv);
    double worst = 0;
    for (int k = 0; k < kFeatureSamples; ++k) worst = std::max(worst, double(std::abs(g[size_t(k)] - h[size_t(k)])));
    EXPECT_LT(worst, 0.02) << "transform " << t;
  }
  // The feature is the same at any size and place, and differs for another shape.
  Outline big = o;
  for (auto& p : big) p = 37.0 * p + Vec2(5, -3);
  EXPECT_LT(feature_distance(circle_feature(big), f), 0.003);
  const TriMesh cyl = normalize_to_principal_axes(make_base_model(standard_base_specs(3)[7 * 3]));
  EXPECT_GT(feature_distance(circle_feature(mesh_outline(cyl, 1, 3)), f), 0.05);
}

TEST(BaseLibrary, OrientationsKeepFacesOutwards) {
  // All 48 ways of facing the views; a mirror must turn the faces round (positive volume).
  const TriMesh m = make_base_model(standard_base_specs(1)[8]);  // a closed sphere
  auto volume = [](const TriMesh& t) {
    double v = 0;
    for (const auto& f : t.faces) v += t.vertices[size_t(f[0])].dot(t.vertices[size_t(f[1])].cross(t.vertices[size_t(f[2])])) / 6;
    return v;
  };
  ASSERT_GT(volume(m), 0);
  const auto all = all_axis_orientations();
  ASSERT_EQ(all.size(), 48u);
  int mirrors = 0;
  for (const auto& o : all) {
    mirrors += o.mirrors();
    EXPECT_NEAR(volume(oriented(m, o)), volume(m), 1e-9 * std::abs(volume(m)));
  }
  EXPECT_EQ(mirrors, 24);
}

TEST(BaseLibrary, HausdorffDistanceOfKnownOutlines) {
  // Squares of side 1: one shifted by 0.3, one far away (100.3); a square of side 3 around one of
  // side 1 in its middle: the big one's corners are sqrt 2 from the small one's (and no point of
  // the small one is farther than 1 from the big one).
  auto square = [](double x, double y, double side) {
    return Outline{Vec2(x, y), Vec2(x + side, y), Vec2(x + side, y + side), Vec2(x, y + side)};
  };
  EXPECT_NEAR(outline_hausdorff(square(0, 0, 1), square(0.3, 0, 1)), 0.3, 1e-5);
  EXPECT_NEAR(outline_hausdorff(square(0, 0, 1), square(100.3, 0, 1)), 100.3, 1e-5);
  EXPECT_NEAR(outline_hausdorff(square(0, 0, 3), square(1, 1, 1)), std::sqrt(2.0), 1e-5);
  EXPECT_NEAR(outline_hausdorff(square(1, 1, 1), square(0, 0, 3)), std::sqrt(2.0), 1e-5);
}

TEST(BaseLibrary, OutlineOfADrawnFigure) {
  // An ellipse drawn with two breaks in its line, hatching inside, a caption and paper noise.
  Outline ellipse;
  for (int k = 0; k < 200; ++k) ellipse.push_back(Vec2(1.5 * std::cos(2 * M_PI * k / 200), std::sin(2 * M_PI * k / 200)));
  std::mt19937 rng(3);
  cv::Vec3d t;
  const cv::Mat img = rktest::draw_figure(ellipse, {}, rng, &t);
  const auto found = drawing_outlines(drawing_grey(img), cv::Rect(), 1);
  ASSERT_EQ(found.size(), 1u);
  EXPECT_GE(found[0].dropped, 1);  // the caption
  const double h = outline_hausdorff(found[0].outline, rktest::outline_in_pixels(ellipse, t));
  EXPECT_LT(h, 5.0) << "px";  // measured 3.4 px: the outline is the outer edge of a 3-px line
  // A region holding no closed line, and a blank page: a clear error.
  cv::Mat stroke(300, 300, CV_8UC1, cv::Scalar(255));
  cv::line(stroke, {20, 150}, {280, 160}, cv::Scalar(0), 3);
  try {
    drawing_outlines(drawing_grey(stroke), cv::Rect(), 1);
    FAIL() << "an open stroke gave an outline";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("No closed outline"), std::string::npos) << e.what();
  }
  EXPECT_THROW(drawing_outlines(drawing_grey(cv::Mat(200, 200, CV_8UC1, cv::Scalar(255))), cv::Rect(), 1), InputError);
  EXPECT_THROW(drawing_outlines(drawing_grey(img), cv::Rect(5000, 5000, 100, 100), 1), InputError);
}

TEST(BaseLibrary, RetrievalFindsTheClassOfHeldOutModels) {
  const BaseLibrary& lib = memory_library();
  ASSERT_EQ(lib.models.size(), size_t(36 * kBaseClasses));
  // Held-out models: other proportions (another seed), drawn in front view turned up to 20
  // degrees about their axis, either way round, with breaks, hatching, caption and noise.
  const auto held_out = standard_base_specs(10, 777);
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> yaw(-20, 20);
  int right = 0, total = 0, right_two = 0;
  std::map<std::string, int> wrong;
  for (const auto& s : held_out) {
    const TriMesh m = rktest::upright(make_base_model(s), yaw(rng), rng() % 2);
    const Outline front = flip_y(drawn_outline(mesh_outline(m, ViewKind::Front, 600), rng));
    const auto best = retrieve_bases(lib, {{ViewKind::Front, circle_feature(front)}}, 1);
    const bool ok = lib.models[size_t(best[0].model)].kind == base_class_name(s.kind);
    right += ok;
    if (!ok) ++wrong[std::string(base_class_name(s.kind)) + "->" + lib.models[size_t(best[0].model)].kind];
    ++total;
    // Front and top views together.
    if (s.variant < 4) {
      const Outline top = flip_y(drawn_outline(mesh_outline(m, ViewKind::Top, 600), rng));
      const auto two = retrieve_bases(lib, {{ViewKind::Front, circle_feature(front)}, {ViewKind::Top, circle_feature(top)}}, 1);
      right_two += lib.models[size_t(two[0].model)].kind == base_class_name(s.kind);
    }
  }
  std::string confusions;
  for (const auto& [k, n] : wrong) confusions += k + " x" + std::to_string(n) + " ";
  const double rate = double(right) / total;
  std::printf("top-1 class, front view: %d / %d = %.3f; front + top: %d / %d (%s)\n", right, total, rate, right_two,
              4 * kBaseClasses, confusions.c_str());
  EXPECT_GE(rate, 0.90) << confusions;
  EXPECT_GE(right_two, int(0.9 * 4 * kBaseClasses));
}

// A model of class `kind` (the library's specs, seed 1) deformed to the drawn outline of another
// model of its class (seed 99: other proportions; drawn as a figure and found again).
struct ClassFit {
  std::vector<ViewOutline> views;
  TriMesh placed, out;
  DeformReport rep;
};
ClassFit fit_to_another_of_its_class(int kind, const DeformParams& params, std::mt19937& rng) {
  const TriMesh model = rktest::upright(make_base_model(standard_base_specs(2)[size_t(2 * kind)]));
  const TriMesh target = rktest::upright(make_base_model(standard_base_specs(2, 99)[size_t(2 * kind + 1)]));
  ClassFit fit;
  fit.views = {{ViewKind::Front, flip_y(drawn_outline(mesh_outline(target, ViewKind::Front, 600), rng))}};
  fit.placed = place_on_outlines(model, fit.views);
  fit.out = deform_to_outlines(fit.placed, fit.views, params, &fit.rep);
  return fit;
}

TEST(BaseLibrary, DeformationFitsTheOutline) {
  // A model of every class deformed to the drawn outline of another model of its class (other
  // proportions; drawn as a figure and found again). Measured (5 passes, alpha 1): 0.2 - 0.8 % of
  // the outline's size for the seven classes whose silhouette is one body; the jug and the
  // amphora keep 1.5 - 1.7 %, in the notch where a handle meets the neck.
  std::mt19937 rng(5);
  const auto lib = standard_base_specs(2);
  const auto other = standard_base_specs(2, 99);
  std::vector<double> errors;
  for (int kind = 0; kind < kBaseClasses; ++kind) {
    const ClassFit fit = fit_to_another_of_its_class(kind, {}, rng);
    const DeformReport& rep = fit.rep;
    const TriMesh &placed = fit.placed, &out = fit.out;
    const auto& views = fit.views;
    std::printf("%s: Hausdorff %.4f -> %.4f of the outline, Laplacian change %.3f, %d silhouette vertices\n",
                base_class_name(kind), rep.hausdorff_before, rep.hausdorff_after, rep.laplacian_change, rep.silhouette_vertices);
    const bool handle_at_neck = kind == 4 || kind == 5;
    EXPECT_LT(rep.hausdorff_after, handle_at_neck ? 0.025 : 0.01) << base_class_name(kind);
    EXPECT_LT(rep.hausdorff_after, 0.6 * rep.hausdorff_before) << base_class_name(kind);
    EXPECT_LT(rep.laplacian_change, 1.0) << base_class_name(kind);
    EXPECT_NEAR(silhouette_error(out, views), rep.hausdorff_after, 1e-9);
    // Depth kept: a front view alone changes the model's depth (z) extent little.
    double z0 = 0, z1 = 0;
    for (const auto& p : placed.vertices) z0 = std::max(z0, std::abs(p.z()));
    for (const auto& p : out.vertices) z1 = std::max(z1, std::abs(p.z()));
    EXPECT_NEAR(z1 / z0, 1.0, 0.35) << base_class_name(kind);
    errors.push_back(rep.hausdorff_after);
  }
  std::nth_element(errors.begin(), errors.begin() + errors.size() / 2, errors.end());
  EXPECT_LT(errors[errors.size() / 2], 0.008);
  // The thesis' single solve moves less of the way.
  const TriMesh model = rktest::upright(make_base_model(lib[2]));
  const Outline drawn = flip_y(drawn_outline(mesh_outline(rktest::upright(make_base_model(other[3])), ViewKind::Front, 600), rng));
  DeformParams one;
  one.passes = 1;
  DeformReport r1, r5;
  const std::vector<ViewOutline> views = {{ViewKind::Front, drawn}};
  deform_to_outlines(place_on_outlines(model, views), views, one, &r1);
  deform_to_outlines(place_on_outlines(model, views), views, {}, &r5);
  EXPECT_LT(r1.hausdorff_after, r1.hausdorff_before);
  EXPECT_LT(r5.hausdorff_after, r1.hausdorff_after);
}

TEST(BaseLibrary, DeformationOnACoarseCopyFitsTheOutline) {
  // The passes of a large model solve on a coarse copy (coarsening.h) and move the model as the
  // copy moves. The library's models (6-18 K faces) forced onto copies of at most 2,000 faces — a
  // coarser copy than a 100 K-face model gets at the default 20,000 — still fit as the model
  // itself does. Measured: 0.18 - 1.62 % of the outline's size (median 0.82 %), the Laplacian
  // coordinates changed 0.03 - 0.47.
  std::mt19937 rng(5);
  DeformParams p;
  p.coarse_faces = 2000;
  std::vector<double> errors;
  for (int kind = 0; kind < kBaseClasses; ++kind) {
    const ClassFit fit = fit_to_another_of_its_class(kind, p, rng);
    const DeformReport& rep = fit.rep;
    std::printf("%s on a copy of %d faces: Hausdorff %.4f -> %.4f, Laplacian change %.3f\n", base_class_name(kind),
                rep.coarse_faces, rep.hausdorff_before, rep.hausdorff_after, rep.laplacian_change);
    EXPECT_GT(rep.coarse_faces, 0) << base_class_name(kind);
    EXPECT_LE(rep.coarse_faces, 2000) << base_class_name(kind);
    EXPECT_LT(rep.hausdorff_after, 0.03) << base_class_name(kind);
    EXPECT_LT(rep.hausdorff_after, 0.6 * rep.hausdorff_before) << base_class_name(kind);
    EXPECT_LT(rep.laplacian_change, 1.0) << base_class_name(kind);
    EXPECT_NEAR(silhouette_error(fit.out, fit.views), rep.hausdorff_after, 1e-9);
    errors.push_back(rep.hausdorff_after);
  }
  std::nth_element(errors.begin(), errors.begin() + errors.size() / 2, errors.end());
  EXPECT_LT(errors[errors.size() / 2], 0.015);
}

TEST(BaseLibrary, UnreferencedVerticesDoNotUnsettleTheCoarseCopy) {
  // Scans carry vertices in no face (the Stanford bunny of ../shared/data: 1,113). Each is an
  // aggregate of its own on the coarse copy, held by nothing but the anchor: were it to carry
  // values to the surface near it, the solve would use it freely (the bunny's silhouette went
  // 4.6 % -> 329 % off). A cup with 400 such vertices scattered on its surface fits as without them.
  std::mt19937 rng(8);
  const TriMesh cup = rktest::upright(make_base_model(standard_base_specs(2)[4]));
  const Outline drawn = flip_y(drawn_outline(
      mesh_outline(rktest::upright(make_base_model(standard_base_specs(2, 99)[5])), ViewKind::Front, 600), rng));
  const std::vector<ViewOutline> views = {{ViewKind::Front, drawn}};
  TriMesh scan = cup;
  std::uniform_int_distribution<int> pick(0, cup.n_vertices() - 1);
  for (int k = 0; k < 400; ++k) scan.vertices.push_back(cup.vertices[size_t(pick(rng))] * 1.001);
  DeformParams p;
  p.coarse_faces = 2000;
  DeformReport clean, with_loose;
  deform_to_outlines(place_on_outlines(cup, views), views, p, &clean);
  const TriMesh out = deform_to_outlines(place_on_outlines(scan, views), views, p, &with_loose);
  std::printf("cup on a copy: %.4f; with 400 unreferenced vertices: %.4f\n", clean.hausdorff_after, with_loose.hausdorff_after);
  EXPECT_GT(with_loose.coarse_faces, 0);
  EXPECT_LT(with_loose.hausdorff_after, 0.015);
  EXPECT_NEAR(with_loose.hausdorff_after, clean.hausdorff_after, 0.005);
  for (const auto& v : out.vertices) ASSERT_TRUE(v.allFinite());
}

TEST(BaseLibrary, CylinderBecomesAGoblet) {
  // Thesis fig. 7.10 (a): the deformation starts from a cylinder and yields the goblet.
  BaseModelSpec cyl = standard_base_specs(1)[7];
  TriMesh model = rktest::upright(make_base_model(cyl, 128));
  const std::vector<ViewOutline> views = {{ViewKind::Front, rktest::goblet_outline()}};
  const TriMesh placed = place_on_outlines(model, views);
  DeformReport rep;
  deform_to_outlines(placed, views, {}, &rep);
  std::printf("cylinder -> goblet: Hausdorff %.4f -> %.4f, Laplacian change %.3f\n", rep.hausdorff_before,
              rep.hausdorff_after, rep.laplacian_change);
  // Measured 3.5 % (5 passes): the drawn goblet's sharp corners are rounded; one solve: 19 %.
  EXPECT_GT(rep.hausdorff_before, 0.25);
  EXPECT_LT(rep.hausdorff_after, 0.05);
}

// Where the views put the model: a top view is (x, -z), a side view (-z, y) of the world (the
// drawing's frame). A lamp turned 30 deg about its axis (no view of it symmetric), scaled by 2.5 and
// moved by (3, -2, 5), drawn in each view: placed from those outlines alone it must land on that
// copy along the axes the views see — z from a top or a side view with its sign — and the
// deformation, with nothing to change, must leave it there.
TEST(BaseLibrary, TopAndSideViewsPlaceTheModelWithTheirAxesSigns) {
  const TriMesh model = rktest::upright(make_base_model(standard_base_specs(1)[0]), 30);
  const Vec3 shift(3, -2, 5);
  TriMesh target = model;
  for (auto& p : target.vertices) p = 2.5 * p + shift;
  double size = 0;
  for (const auto& p : target.vertices) size = std::max(size, (p - shift).norm());
  using Views = std::vector<ViewKind>;
  for (const Views& kinds : {Views{ViewKind::Top}, Views{ViewKind::Side}, Views{ViewKind::Front, ViewKind::Top, ViewKind::Side}}) {
    std::vector<ViewOutline> views;
    Vec3 seen = Vec3::Zero();  // the world axes these views see
    for (ViewKind k : kinds) {
      views.push_back({k, mesh_outline(target, k, 512)});
      seen += Vec3::Ones() - Vec3::Unit(view_depth_axis(k));
    }
    const TriMesh placed = place_on_outlines(model, views);
    double worst = 0;
    for (size_t i = 0; i < placed.vertices.size(); ++i)
      for (int a = 0; a < 3; ++a)
        if (seen[a] > 0) worst = std::max(worst, std::abs(placed.vertices[i][a] - target.vertices[i][a]));
    std::string names;
    for (ViewKind k : kinds) names += std::string(names.empty() ? "" : " + ") + view_name(k);
    std::printf("[placement] %s: largest offset from the true place %.2e of the model's size\n", names.c_str(), worst / size);
    // Measured: 0 (2e-16); with a top or side view's axis sign ignored, 2.6 x the model's size.
    EXPECT_LT(worst / size, 1e-9) << names;
    if (kinds.size() < 3) continue;
    DeformReport rep;
    const TriMesh out = deform_to_outlines(placed, views, {}, &rep);
    double moved = 0;
    for (size_t i = 0; i < out.vertices.size(); ++i) moved = std::max(moved, (out.vertices[i] - target.vertices[i]).norm());
    std::printf("[placement] deformed to the three views: Hausdorff %.4f -> %.4f of the outline, largest offset from the "
                "true place %.2e of the model's size\n", rep.hausdorff_before, rep.hausdorff_after, moved / size);
    // Measured: Hausdorff 0.0013 -> 0.0040 (the passes move a model that already fits by up to
    // 3.4 % of its size, mostly along its surface); with the views' signs ignored when the matched
    // outline points are taken back to the world: 1.62, and vertices 2.6 x the size away.
    EXPECT_LT(rep.hausdorff_after, 0.01);
    EXPECT_LT(moved / size, 0.1);
  }
}

TEST(BaseLibrary, ModelFolderAndItsCache) {
  const fs::path dir = fs::temp_directory_path() / ("rk_models_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir / "lamps");
  const auto specs = standard_base_specs(1);
  write_model_ply((dir / "lamps" / "my_lamp.ply").string(), make_base_model(specs[0]));
  // The same bowl as OBJ and as ASCII STL.
  const TriMesh bowl = make_base_model(specs[1]);
  {
    std::ofstream obj(dir / "bowl_a.obj"), stl(dir / "bowl_b.stl");
    for (const auto& p : bowl.vertices) obj << "v " << p.x() << ' ' << p.y() << ' ' << p.z() << '\n';
    for (const auto& f : bowl.faces) obj << "f " << f[0] + 1 << ' ' << f[1] + 1 << ' ' << f[2] + 1 << '\n';
    stl << "solid bowl\n";
    for (const auto& f : bowl.faces) {
      stl << "facet normal 0 0 0\nouter loop\n";
      for (int k = 0; k < 3; ++k) { const auto& p = bowl.vertices[size_t(f[size_t(k)])]; stl << "vertex " << p.x() << ' ' << p.y() << ' ' << p.z() << '\n'; }
      stl << "endloop\nendfacet\n";
    }
    stl << "endsolid bowl\n";
    std::ofstream(dir / "broken.ply") << "ply\nformat ascii 1.0\nelement vertex 3\nend_header\n1 2\n";
    std::ofstream(dir / "notes.txt") << "not a model";
  }
  BaseLibrary lib;
  add_library_folder(lib, dir.string());
  ASSERT_EQ(lib.models.size(), 3u);
  bool skipped = false, cached = false;
  for (const auto& n : lib.notes) {
    skipped |= n.find("broken.ply") != std::string::npos;
    cached |= n.find("cached") != std::string::npos;
  }
  EXPECT_TRUE(skipped);
  EXPECT_TRUE(cached);
  EXPECT_TRUE(fs::exists(dir / kFeatureCache));
  std::map<std::string, LibraryModel> by;
  for (const auto& m : lib.models) by[m.name] = m;
  EXPECT_EQ(by["my_lamp"].kind, "lamps");
  EXPECT_EQ(by["bowl_a"].kind, "bowl");
  for (int k = 0; k < 3; ++k) EXPECT_LT(feature_distance(by["bowl_a"].feature[size_t(k)], by["bowl_b"].feature[size_t(k)]), 1e-3);
  // Second read: from the cache (no recomputation note), same features.
  BaseLibrary again;
  add_library_folder(again, dir.string());
  ASSERT_EQ(again.models.size(), 3u);
  for (const auto& n : again.notes) EXPECT_EQ(n.find("computed"), std::string::npos) << n;
  for (const auto& m : again.models)
    for (int k = 0; k < 3; ++k) EXPECT_LT(feature_distance(m.feature[size_t(k)], by[m.name].feature[size_t(k)]), 1e-6);
  // A copy of the folder with new file dates (as cp, an install or a checkout makes them) keeps the
  // cache: matched by content, nothing computed, the new dates recorded.
  const fs::path copy = dir.string() + "_copy";
  fs::remove_all(copy);
  fs::copy(dir, copy, fs::copy_options::recursive);
  for (const auto& e : fs::recursive_directory_iterator(copy))
    if (e.is_regular_file()) fs::last_write_time(e.path(), fs::last_write_time(e.path()) + std::chrono::hours(1));
  BaseLibrary copied;
  add_library_folder(copied, copy.string());
  ASSERT_EQ(copied.models.size(), 3u);
  bool matched = false;
  for (const auto& n : copied.notes) {
    EXPECT_EQ(n.find("computed"), std::string::npos) << n;
    matched |= n.find("same content") != std::string::npos;
  }
  EXPECT_TRUE(matched);
  for (const auto& m : copied.models)
    for (int k = 0; k < 3; ++k) EXPECT_LT(feature_distance(m.feature[size_t(k)], by[m.name].feature[size_t(k)]), 1e-6);
  fs::remove_all(copy);
  // An empty folder gives no model; a missing one is an error.
  fs::create_directories(dir / "empty");
  BaseLibrary none;
  add_library_folder(none, (dir / "empty").string());
  EXPECT_TRUE(none.models.empty());
  EXPECT_THROW(add_library_folder(none, (dir / "missing").string()), InputError);
  EXPECT_THROW(read_model_file((dir / "broken.ply").string()), InputError);
  fs::remove_all(dir);
}

TEST(BaseLibrary, BadDeformationInput) {
  TriMesh m = rktest::upright(make_base_model(standard_base_specs(1)[7]));
  const std::vector<ViewOutline> views = {{ViewKind::Front, rktest::goblet_outline()}};
  DeformParams p;
  p.alpha = 0;
  EXPECT_THROW(deform_to_outlines(m, views, p), InputError);
  p.alpha = std::nan("");
  EXPECT_THROW(deform_to_outlines(m, views, p), InputError);
  m.vertices[3].x() = std::nan("");
  EXPECT_THROW(deform_to_outlines(m, views, {}), InputError);
  EXPECT_THROW(deform_to_outlines(TriMesh{}, views, {}), InputError);
  EXPECT_THROW(deform_to_outlines(rktest::upright(make_base_model(standard_base_specs(1)[7])), {{ViewKind::Front, {}}}, {}),
               InputError);
}

// Which outline is which view (find_view_outlines): two figures on one page are the front (top)
// and top (below) views in reading order; a view with its own image and one with a region take
// theirs; a page with fewer outlines than views stops with the count.
TEST(BaseLibrary, ViewsTakeTheirOutlinesInReadingOrderOrFromTheirOwnImageOrRegion) {
  cv::Mat page(400, 300, CV_8UC1, cv::Scalar(255)), side(200, 200, CV_8UC1, cv::Scalar(255));
  cv::rectangle(page, cv::Point(50, 30), cv::Point(250, 150), cv::Scalar(0), 3);  // drawn first: the front
  cv::circle(page, cv::Point(150, 290), 80, cv::Scalar(0), 3);                     // below it: the top
  cv::ellipse(side, cv::Point(100, 100), cv::Size(60, 40), 0, 0, 360, cv::Scalar(0), 3);
  const ViewImage drawing{drawing_grey(page), 0.5}, own{drawing_grey(side), 0.25};
  std::vector<std::string> asked;
  auto image_of = [&](const std::string& name) -> const ViewImage& {
    asked.push_back(name);
    return name.empty() ? drawing : own;
  };
  const auto found = find_view_outlines(parse_drawing_views("front; top; side = side.png"), image_of);
  ASSERT_EQ(found.size(), 3u);
  EXPECT_NEAR(found[0].outline.box.y, 30, 3);   // the rectangle
  EXPECT_NEAR(found[1].outline.box.y, 210, 3);  // the circle
  EXPECT_EQ(found[0].pixel_size, 0.5);
  EXPECT_NEAR(found[2].outline.box.width, 124, 2);  // the side image's ellipse: 2 x (60 + 1.5) + 1 px, the line's outer edge
  EXPECT_EQ(found[2].pixel_size, 0.25);
  EXPECT_EQ(found[2].frame, cv::Rect(0, 0, 200, 200));
  ASSERT_FALSE(asked.empty());
  EXPECT_EQ(asked.front(), "");  // the drawing is read first, whatever the views
  const auto region = find_view_outlines(parse_drawing_views("front = 0 200 300 200"), image_of);
  EXPECT_NEAR(region[0].outline.box.y, 210, 3);
  EXPECT_EQ(region[0].frame, cv::Rect(0, 200, 300, 200));
  try {
    find_view_outlines(parse_drawing_views("front; top; side"), image_of);
    FAIL() << "three views from two outlines";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("need 3 separate outlines, but the drawing has 2"), std::string::npos) << e.what();
  }
}

// The poor-fit rule: a base left more than 5 % of the outline's size off it is warned about.
TEST(BaseLibrary, APoorFitIsWarnedAbout) {
  DeformReport fits, poor;
  fits.hausdorff_after = 0.049, poor.hausdorff_after = 0.08;
  EXPECT_EQ(base_fit_warning(fits), "");
  EXPECT_EQ(base_fit_warning(poor).rfind("Warning: the base stays 8.0 % of the outline's size off the drawing", 0), 0u)
      << base_fit_warning(poor);
}
