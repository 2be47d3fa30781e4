// rk_make_mesh — writes the synthetic test surfaces as binary PLY (for benchmarks and docs).
//   rk_make_mesh torus R r nu nv jitter seed out.ply
//   rk_make_mesh relief-torus FACES out.ply      (jittered torus with bumps, ~FACES faces)
//   rk_make_mesh sphere r levels jitter out.ply
//   rk_make_mesh flake SEED out.ply [aretes.xyz] (a knapped flake whose arêtes are known; flakes.h)
//   rk_make_mesh convert in.obj|in.ply out.ply   (e.g. OBJ files MeshLab 2020.09's importer aborts on)
//   rk_make_mesh nested-drawing out.png          (the synthetic line drawing of the drawing tests)
//   rk_make_mesh base-figure CLASS SEED ft out.png (a base-library class drawn in front and top view)
//   rk_make_mesh goblet-figure out.png           (the goblet of thesis fig. 7.8, front view)
//   rk_make_mesh dome W H cell out.ply           (a smooth dome W x H, cell apart: a base for drawings)
//   rk_make_mesh sherd jar|bowl|beaker SPAN FROM TO NOISE SEED out.ply
//                                                (a vessel or sherd of known profile, random pose, mm; sherds.h)
//   rk_make_mesh turned cylinder|cone|globe RELIEF DESIGN SEED out.ply
//                                                (a seal, cone or belly with a design of known height, random pose; turned.h;
//                                                 DESIGN 0: five bumps, 1: a band, 2: a frieze of figures)
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <Eigen/Geometry>
#include <string>

#include <opencv2/imgcodecs.hpp>
#include <stdexcept>

#include "bases.h"
#include "drawings.h"
#include "finds.h"
#include "flakes.h"
#include "mesh_files.h"
#include "shapes.h"
#include "sherds.h"
#include "turned.h"

int main(int argc, char** argv) {
  std::string kind = argc > 1 ? argv[1] : "";
  try {
    if (kind == "convert" && argc == 4) {
      rktest::write_ply(argv[3], rktest::read_mesh(argv[2]).mesh);
    } else if (kind == "sherd" && argc == 9) {
      rktest::SherdOptions o;
      const std::string shape = argv[2];
      o.shape = shape == "bowl" ? rktest::VesselShape::bowl : shape == "beaker" ? rktest::VesselShape::beaker : rktest::VesselShape::jar;
      o.span_deg = std::atof(argv[3]), o.from = std::atof(argv[4]), o.to = std::atof(argv[5]);
      o.noise = std::atof(argv[6]), o.seed = unsigned(std::atol(argv[7])), o.irregular = true;
      const rktest::Sherd sh = rktest::make_sherd(o);
      rktest::write_ply(argv[8], sh.mesh);
      std::printf("faces %d rim diameter %.4f axis point %.4f %.4f %.4f direction %.6f %.6f %.6f\n", sh.mesh.n_faces(),
                  sh.rim_diameter, sh.axis_point.x(), sh.axis_point.y(), sh.axis_point.z(), sh.axis_direction.x(),
                  sh.axis_direction.y(), sh.axis_direction.z());
    } else if (kind == "turned" && argc == 7) {
      rktest::TurnedOptions o;
      const std::string shape = argv[2];
      o.shape = shape == "cone" ? rktest::TurnedShape::cone : shape == "globe" ? rktest::TurnedShape::globe : rktest::TurnedShape::cylinder;
      if (o.shape == rktest::TurnedShape::globe) o.radius = 20, o.length = 24;
      o.relief = std::atof(argv[3]), o.band = std::atoi(argv[4]) == 1, o.frieze = std::atoi(argv[4]) == 2;
      o.seed = unsigned(std::atol(argv[5])), o.irregular = true;
      const rktest::Turned t = rktest::make_turned(o);
      rktest::write_ply(argv[6], t.mesh);
      std::printf("faces %d middle radius %.4f axis point %.4f %.4f %.4f direction %.6f %.6f %.6f\n", t.mesh.n_faces(), t.middle_radius,
                  t.axis_point.x(), t.axis_point.y(), t.axis_point.z(), t.axis_direction.x(), t.axis_direction.y(), t.axis_direction.z());
    } else if (kind == "torus" && argc == 9) {
      auto m = rktest::torus(std::atof(argv[2]), std::atof(argv[3]), std::atoi(argv[4]), std::atoi(argv[5]),
                             std::atof(argv[6]), std::atoi(argv[7]));
      rktest::write_ply(argv[8], m);
    } else if (kind == "flake" && (argc == 4 || argc == 5)) {
      rktest::FlakeShape shape;
      shape.seed = uint32_t(std::atol(argv[2]));
      const rktest::Flake f = rktest::knapped_flake(shape);
      rktest::write_ply(argv[3], f.relief.mesh);
      if (argc == 5) {  // the arêtes' samples, "x y z" per line
        std::FILE* out = std::fopen(argv[4], "w");
        if (!out) throw std::runtime_error("cannot write the arêtes");
        for (const auto& p : f.relief.boundary) std::fprintf(out, "%.9g %.9g %.9g\n", p.x(), p.y(), p.z());
        std::fclose(out);
      }
      std::printf("faces %d mean_edge %.9g arete_samples %zu\n", f.relief.mesh.n_faces(), f.relief.mean_edge,
                  f.relief.boundary.size());
    } else if (kind == "relief-torus" && argc == 4) {
      auto m = rktest::relief_torus(std::atol(argv[2]));
      rktest::write_ply(argv[3], m);
      std::printf("faces %d mean_edge %.9g\n", m.n_faces(), reliefkit::edge_length_stats(m).mean);
    } else if (kind == "nested-drawing" && argc == 3) {
      if (!cv::imwrite(argv[2], rktest::nested_drawing())) throw std::runtime_error("cannot write the drawing");
    } else if (kind == "base-figure" && argc == 6) {
      // A library-class model (class index, seed) drawn in the views given as letters: f front, s side, t top.
      reliefkit::BaseModelSpec spec;
      spec.kind = std::atoi(argv[2]);
      spec.seed = unsigned(std::atol(argv[3]));
      spec.variant = int(spec.seed % 6);
      std::vector<reliefkit::ViewKind> views;
      for (const char* c = argv[4]; *c; ++c)
        views.push_back(*c == 't' ? reliefkit::ViewKind::Top : *c == 's' ? reliefkit::ViewKind::Side : reliefkit::ViewKind::Front);
      std::mt19937 rng(spec.seed);
      rktest::FigureStyle style;
      style.size = 500;
      const cv::Mat img = rktest::draw_views(rktest::upright(reliefkit::make_base_model(spec)), views, style, rng);
      if (!cv::imwrite(argv[5], img)) throw std::runtime_error("cannot write the figure");
    } else if (kind == "goblet-figure" && argc == 3) {
      std::mt19937 rng(1);
      if (!cv::imwrite(argv[2], rktest::draw_figure(rktest::goblet_outline(), {}, rng))) throw std::runtime_error("cannot write the figure");
    } else if (kind == "dome" && argc == 6) {
      const int w = std::atoi(argv[2]), h = std::atoi(argv[3]);
      reliefkit::TriMesh m = reliefkit::drawing_grid(w, h, std::atof(argv[4]), 1.0);
      const double R = 1.5 * std::max(w, h);
      for (auto& v : m.vertices) {
        const double x = v.x() - 0.5 * (w - 1), y = v.y() + 0.5 * (h - 1);
        v.z() = std::sqrt(R * R - x * x - y * y) - R;
      }
      rktest::write_ply(argv[5], m);
    } else if (kind == "sphere" && argc == 6) {
      rktest::write_ply(argv[5], rktest::sphere(std::atof(argv[2]), std::atoi(argv[3]), std::atof(argv[4])));
    } else if ((kind == "tablet" || kind == "blade" || kind == "coin") && argc == 4) {
      // upright: as finds.h makes them (the obverse or dorsal face towards +z, up +y); lying: on
      // the scanner's table, that face up (+y), the top or tip away (-z)
      const std::string pose = argv[2];
      const reliefkit::Mat3 turn = pose == "lying" ? reliefkit::Mat3(Eigen::AngleAxisd(-M_PI / 2, reliefkit::Vec3::UnitX())) : reliefkit::Mat3::Identity();
      const rktest::Find f = kind == "tablet" ? rktest::tablet({}, turn) : kind == "blade" ? rktest::blade({}, turn) : rktest::coin({}, turn);
      rktest::write_ply(argv[3], f.mesh);
      std::printf("faces %d width %.2f height %.2f thickness through the middle %.2f\n", f.mesh.n_faces(), f.width, f.height,
                  f.thickness_at_middle);
    } else {
      std::fprintf(stderr, "usage: rk_make_mesh tablet|blade|coin upright|lying out.ply | torus R r nu nv jitter seed out.ply | relief-torus FACES out.ply | flake SEED out.ply | "
                           "sphere r levels jitter out.ply | nested-drawing out.png | dome W H cell out.ply | base-figure CLASS SEED VIEWS(fst) out.png | "
                           "goblet-figure out.png\n");
      return 2;
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "rk_make_mesh: %s\n", e.what());
    return 1;
  }
  return 0;
}
