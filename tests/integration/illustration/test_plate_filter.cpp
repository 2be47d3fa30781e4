// "Export Illustration Plate" through the real meshlabserver: a disc of radius 0.5 raised on a
// plane, its demarcating curves drawn from above at 1:1 with the mesh unit 50 mm — every point of
// the SVG's paths on the circle of 25 mm, the page, the PDF read by pdfinfo and drawn by pdftoppm,
// the SVG drawn by rsvg-convert; bad input.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <filesystem>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <opencv2/imgcodecs.hpp>
#include <regex>
#include <sstream>

#include "bad_input.h"
#include "finds.h"
#include "mesh_files.h"
#include "reliefs.h"
#include "server.h"

using namespace rktest;
using reliefkit::Mat3;
using reliefkit::Vec3;

namespace {

std::string demarcating() {
  return mlx_filter("Demarcating Curves", {param_float("threshold", 1), param_string("presmoothing", "auto"),
                                           param_float("min_length", 4), param_bool("per_vertex", true),
                                           param_bool("quality", false), param_float("lift", 0)});
}

struct PlateOptions {
  double unit_mm = 50, ratio = 1;
  int section = 0;  // none, vertical, horizontal
  int layout = 0, shading = 0, light_stack = 0;
  std::string reverse_layer;
};

std::string plate(const std::string& file, int view, int page, const std::string& layers = "all", PlateOptions o = {}) {
  return mlx_filter("Export Illustration Plate",
                    {param_save_file("file", file, "*.svg"), param_bool("pdf", true), param_string("layers", layers),
                     param_enum("view", view, 3), param_point("direction", 0, 0, -1), param_enum("layout", o.layout, 5),
                     param_bool("turn_over", false), param_bool("upside_down", false), param_string("reverse_layer", o.reverse_layer),
                     param_float("unit_mm", o.unit_mm), param_float("ratio", o.ratio), param_enum("shading", o.shading, 8),
                     param_float("light_azimuth", 315), param_float("light_elevation", 20), param_float("openness_radius", 10),
                     param_int("light_stack", o.light_stack), param_int("dpi", 150), param_float("width", 0.35),
                     param_enum("weights", 0, 3), param_enum("section", o.section, 3), param_bool("section_fill", true), param_float("section_at", 0.5),
                     param_enum("page", page, 3)});
}

std::string read_text(const std::string& path) {
  std::ifstream f(path);
  std::stringstream s;
  s << f.rdbuf();
  return s.str();
}

std::string command_output(const std::string& cmd) {
  std::string out;
  FILE* p = popen(cmd.c_str(), "r");
  char buf[512];
  while (fgets(buf, sizeof buf, p)) out += buf;
  pclose(p);
  return out;
}
}  // namespace

TEST(PlateFilter, TheDiscsOutlineIsDrawnToScale) {
  const Relief r = disc_on_plane({}, 120);
  std::string dir;
  const ServerRun run = run_filters("plate_disc", r.mesh, {demarcating(), plate("", 1, 0)}, {}, &dir);
  ASSERT_EQ(run.status, 0) << run.output;
  // The file's default place: beside the mesh's file (in.ply), named <mesh>-plate.svg.
  const std::string svg = read_text(dir + "/in-plate.svg");
  ASSERT_FALSE(svg.empty()) << run.output;
  EXPECT_NE(run.output.find("Illustration plate: 120.0 x 132.0 mm at 1:1"), std::string::npos) << run.output;
  // Every path point on the circle of radius 0.5 x 50 mm around the drawing's centre.
  const double cx = 10 + 50, cy = 10 + 50;  // the 100 mm drawing inside its 10 mm margins
  const std::regex pair(R"((-?[0-9.]+),(-?[0-9.]+))");
  double worst = 0;
  int points = 0;
  const size_t layer = svg.find("demarcating curves\""), layer_end = svg.find("</g>", layer);
  ASSERT_NE(layer, std::string::npos);
  const std::string curves = svg.substr(layer, layer_end - layer);  // the curve layer's group, not the scale bar's
  for (std::sregex_iterator it(curves.begin(), curves.end(), pair), end; it != end; ++it) {
    const double x = std::stod((*it)[1]), y = std::stod((*it)[2]);
    worst = std::max(worst, std::abs(std::hypot(x - cx, y - cy) - 25));
    ++points;
  }
  std::printf("%d path points, worst %.3f mm off the 25 mm circle\n", points, worst);
  EXPECT_GT(points, 50);
  EXPECT_LT(worst, 0.2);  // measured 0.036 mm (the step's width is 0.04 x 50 = 2 mm)
  // Real renderers: the SVG at 150 dpi, the PDF's page and its drawing.
  ASSERT_EQ(std::system(("rsvg-convert --dpi-x 150 --dpi-y 150 -o '" + dir + "/svg.png' '" + dir + "/in-plate.svg'").c_str()), 0);
  const cv::Mat svg_png = cv::imread(dir + "/svg.png", cv::IMREAD_GRAYSCALE);
  EXPECT_NEAR(svg_png.cols, 120 / 25.4 * 150, 1.5);
  const std::string info = command_output("pdfinfo '" + dir + "/in-plate.pdf'");
  std::smatch size;
  ASSERT_TRUE(std::regex_search(info, size, std::regex(R"(Page size:\s+([0-9.]+) x ([0-9.]+) pts)"))) << info;
  EXPECT_NEAR(std::stod(size[1]), 120 / 25.4 * 72, 1.0) << info;  // 120 x 132 mm (Qt keeps whole points)
  EXPECT_NEAR(std::stod(size[2]), 132 / 25.4 * 72, 1.0) << info;
  ASSERT_EQ(std::system(("pdftoppm -r 50 -png '" + dir + "/in-plate.pdf' '" + dir + "/pdf'").c_str()), 0);
  const cv::Mat pdf_png = cv::imread(dir + "/pdf-1.png", cv::IMREAD_GRAYSCALE);
  ASSERT_FALSE(pdf_png.empty());
  double lo = 255;
  cv::minMaxLoc(pdf_png, &lo);
  EXPECT_LT(lo, 60) << "the PDF has black lines";
}

TEST(PlateFilter, AnA4PageAndBadInput) {
  const Relief r = disc_on_plane({}, 60);
  std::string dir;
  ServerRun run = run_filters("plate_a4", r.mesh, {demarcating(), plate("a4.svg", 0, 1)}, {}, &dir);
  ASSERT_EQ(run.status, 0) << run.output;
  EXPECT_NE(command_output("pdfinfo '" + dir + "/a4.pdf'").find("(A4)"), std::string::npos);
  // The scale chosen (the disc 20 mm across at 10 mm per unit: 5:1 is the largest that fits A4)
  // and a section's profile beside the drawing.
  run = run_filters("plate_auto", r.mesh, {demarcating(), plate("auto.svg", 1, 0, "all", {10, 0, 1})}, {}, &dir);
  ASSERT_EQ(run.status, 0) << run.output;
  EXPECT_NE(run.output.find("at 5:1 (automatic)"), std::string::npos) << run.output;
  EXPECT_NE(run.output.find("a section of"), std::string::npos) << run.output;
  const std::string auto_svg = read_text(dir + "/auto.svg");
  EXPECT_NE(auto_svg.find("<g id=\"section\""), std::string::npos);
  EXPECT_NE(auto_svg.find("stroke-dasharray"), std::string::npos);
  EXPECT_EQ(run.output.find("Warning"), std::string::npos) << run.output;  // 20 mm: a plausible size
  // At 1 mm per unit the disc's plane is 2 mm across: the plate is made, and the unit questioned.
  run = run_filters("plate_unit", r.mesh, {demarcating(), plate("unit.svg", 1, 0, "all", {1, 0, 0})}, {}, &dir);
  ASSERT_EQ(run.status, 0) << run.output;
  EXPECT_NE(run.output.find("Warning: the object 2 x 2 mm at 1 mm per unit"), std::string::npos) << run.output;
  // No curve layer: a clear message, no file.
  run = run_filters("plate_no_curves", r.mesh, {plate("none.svg", 0, 0)}, {}, &dir);
  EXPECT_FALSE(run.crashed);
  EXPECT_NE(run.output.find("There is no curve to draw"), std::string::npos) << run.output;
  EXPECT_TRUE(read_text(dir + "/none.svg").empty());
  // A layer asked for by a name that is not there.
  run = run_filters("plate_bad_name", r.mesh, {demarcating(), plate("x.svg", 0, 0, "no such layer")}, {}, &dir);
  EXPECT_NE(run.output.find("No layer is called no such layer"), std::string::npos) << run.output;
  // Names with '*' are patterns: one matching the curve layer draws it, one matching nothing is refused.
  run = run_filters("plate_pattern", r.mesh, {demarcating(), plate("p.svg", 0, 0, "*curves")}, {}, &dir);
  ASSERT_EQ(run.status, 0) << run.output;
  EXPECT_NE(read_text(dir + "/p.svg").find("demarcating curves\""), std::string::npos);
  run = run_filters("plate_pattern_none", r.mesh, {demarcating(), plate("q.svg", 0, 0, "*ridges")}, {}, &dir);
  EXPECT_NE(run.output.find("No layer is called *ridges"), std::string::npos) << run.output;
  // A layer named that is a surface, not curves.
  run = run_filters("plate_surface_named", r.mesh, {demarcating(), plate("x.svg", 0, 0, "in.ply")}, {}, &dir);
  EXPECT_NE(run.output.find("The layer \"in.ply\" holds a surface, not curves"), std::string::npos) << run.output;
  // A drawing of 2 m at 1:1 does not fit an A4 page.
  run = run_filters("plate_too_big", r.mesh,
                    {demarcating(), mlx_filter("Export Illustration Plate",
                                               {param_save_file("file", "big.svg", "*.svg"), param_bool("pdf", false), param_string("layers", "all"),
                                                param_enum("view", 1, 3), param_point("direction", 0, 0, -1), param_enum("layout", 0, 5), param_bool("turn_over", false),
       param_bool("upside_down", false), param_string("reverse_layer", ""),
                                                param_float("unit_mm", 1000), param_float("ratio", 1), param_enum("shading", 0, 8), param_float("light_azimuth", 315), param_float("light_elevation", 20),
       param_float("openness_radius", 10), param_int("light_stack", 0),
                                                param_int("dpi", 50), param_float("width", 0.35), param_enum("weights", 0, 3),
                                                param_enum("section", 0, 3), param_bool("section_fill", true), param_float("section_at", 0.5), param_enum("page", 1, 3)})},
                    {}, &dir);
  EXPECT_NE(run.output.find("Choose a smaller scale or a larger page"), std::string::npos) << run.output;
}

// The damaged meshes every filter is tested on, each with a curve layer loaded beside it (a square
// above the mesh, from an OBJ of lines): a clear message or a plate, never a crash.
TEST(PlateFilter, DamagedMeshesGiveAMessageOrAPlate) {
  expect_bad_input_handled([](const std::string& name, const reliefkit::TriMesh& mesh) {
    const std::string dir = temp_dir("plate_bad_" + name);
    write_ply(dir + "/in.ply", mesh);
    write_text(dir + "/square.obj", "v -0.5 -0.5 2\nv 0.5 -0.5 2\nv 0.5 0.5 2\nv -0.5 0.5 2\nl 1 2\nl 2 3\nl 3 4\nl 4 1\n");
    write_text(dir + "/s.mlx", mlx_script({plate(dir + "/p.svg", 0, 0, "all", {1, 0, 0})}));
    ServerRun run = run_meshlabserver({"-i", dir + "/square.obj", "-i", dir + "/in.ply", "-s", dir + "/s.mlx"});
    if (run.status == 0) EXPECT_NE(read_text(dir + "/p.svg").find("<path"), std::string::npos) << name;
    return run;
  });
}

// A layer a filter made (a relief from a drawing) has no file: the plate's default place is beside
// the document's first file (here the script's input), named after the layer; a full path is
// written where it says.
TEST(PlateFilter, ALayerWithoutAFileGoesBesideTheDocumentsFile) {
  std::string relief = read_text(source_dir() + "/examples/drawing_relief.mlx");
  relief = relief.substr(relief.find("<filter"), relief.find("</filter>") + 9 - relief.find("<filter"));
  // The drawing in a folder of the test's own: the relief writes its interpretation file beside it.
  const std::string drawings = temp_dir("plate_no_file_drawing");
  std::filesystem::copy_file(source_dir() + "/examples/data/nested_drawing.png", drawings + "/nested_drawing.png");
  relief.replace(relief.find("examples/data"), 13, drawings);
  std::string dir;
  ServerRun run = run_filters("plate_no_file", reliefkit::TriMesh{}, {relief, plate("", 1, 0, "all", {1, 0, 0})}, {}, &dir);
  ASSERT_EQ(run.status, 0) << run.output;
  EXPECT_NE(read_text(dir + "/nested_drawing-relief-plate.svg").find("<path"), std::string::npos) << run.output;
  const std::string svg = dir + "/relief.svg";
  run = run_filters("plate_full_path", reliefkit::TriMesh{}, {relief, plate(svg, 1, 0, "all", {1, 0, 0})}, {});
  ASSERT_EQ(run.status, 0) << run.output;
  EXPECT_NE(read_text(svg).find("<path"), std::string::npos);
}

// A scale that is not a number, and a folder that does not exist: a clear message, no crash.
TEST(PlateFilter, ANaNScaleAndAMissingFolderAreRefused) {
  const Relief r = disc_on_plane({}, 60);
  ServerRun run = run_filters("plate_nan_scale", r.mesh, {demarcating(), plate("x.svg", 0, 0, "all", {50, std::nan(""), 0})}, {});
  EXPECT_FALSE(run.crashed) << run.output;
  EXPECT_NE(run.output.find("(\"ratio\") must be between 0 and 1000"), std::string::npos) << run.output;
  run = run_filters("plate_missing_folder", r.mesh, {demarcating(), plate("/no/such/folder/p.svg", 0, 0)}, {});
  EXPECT_FALSE(run.crashed) << run.output;
  EXPECT_NE(run.output.find("could not be written to /no/such/folder/p.svg"), std::string::npos) << run.output;
}

// A layout through meshlabserver: the disc relief as a tablet (six views named on the plate, the
// reverse of this scan of one side "(not scanned)" with the log's warning; one scale bar), under
// openness with a light stack of 4 (the images and the .lp file beside it); two faces asked of a
// layer that is not there: a clear message.
TEST(PlateFilter, ATabletLayoutWithALightStackAndAMissingReverseLayer) {
  const Relief r = disc_on_plane({}, 60);
  PlateOptions o;
  o.ratio = 0.5, o.layout = 1, o.shading = 6, o.light_stack = 4;
  std::string dir;
  ServerRun run = run_filters("plate_tablet", r.mesh, {demarcating(), plate("tablet.svg", 0, 0, "all", o)}, {}, &dir);
  ASSERT_EQ(run.status, 0) << run.output;
  EXPECT_NE(run.output.find("Plate layout: "), std::string::npos) << run.output;
  const std::string svg = read_text(dir + "/tablet.svg");
  EXPECT_NE(run.output.find("Warning: a scan of one side"), std::string::npos) << run.output;
  for (const char* name : {">obverse<", ">reverse (not scanned)<", ">top edge<", ">bottom edge<", ">left edge<", ">right edge<"})
    EXPECT_NE(svg.find(name), std::string::npos) << name;
  EXPECT_EQ(svg.find("<g id=\"scale bar\""), svg.rfind("<g id=\"scale bar\""));  // one scale bar
  const std::string lp = read_text(dir + "/tablet.lp");
  EXPECT_EQ(lp.substr(0, 2), "4\n") << lp;
  for (int k = 1; k <= 4; ++k) EXPECT_TRUE(std::filesystem::exists(dir + "/tablet-light-0" + std::to_string(k) + ".png")) << k;
  o.layout = 3, o.reverse_layer = "no such layer", o.light_stack = 0, o.shading = 0;
  run = run_filters("plate_two_faces", r.mesh, {demarcating(), plate("faces.svg", 0, 0, "all", o)}, {}, &dir);
  EXPECT_FALSE(run.crashed);
  EXPECT_NE(run.output.find("Two faces: no other layer is called \"no such layer\""), std::string::npos) << run.output;
}

// The lithic example script as shipped (examples/lithic_plate.mlx) on a blade (rktest::blade,
// turned over and lying on its side): the dorsal face found, the three views named, the section
// filled below the dorsal face, one scale bar — one filter run from a script.
TEST(PlateFilter, TheLithicExampleDrawsABladeWithItsSection) {
  rktest::BladeOptions b;
  b.levels = 5;
  const Mat3 lying = Eigen::AngleAxisd(M_PI / 2, Vec3::UnitZ()).toRotationMatrix() * Eigen::AngleAxisd(M_PI, Vec3::UnitY()).toRotationMatrix();
  const rktest::Find blade = rktest::blade(b, lying);
  const std::string dir = temp_dir("plate_lithic");
  rktest::write_ply(dir + "/blade.ply", blade.mesh);
  const ServerRun run = run_meshlabserver({"-i", dir + "/blade.ply", "-s", source_dir() + "/examples/lithic_plate.mlx"});
  ASSERT_EQ(run.status, 0) << run.output;
  EXPECT_NE(run.output.find("Plate layout: the dorsal face the less flat"), std::string::npos) << run.output;
  EXPECT_NE(run.output.find("a section of"), std::string::npos) << run.output;
  const std::string svg = read_text(dir + "/blade-plate.svg");
  for (const char* name : {">dorsal face<", ">right profile<", ">ventral face<", ">section<"}) EXPECT_NE(svg.find(name), std::string::npos) << name;
  EXPECT_NE(svg.find("<g id=\"section\""), std::string::npos);
  EXPECT_EQ(svg.find("<g id=\"scale bar\""), svg.rfind("<g id=\"scale bar\""));
  // The arêtes (the ridges, named "*ridges" in the example) are drawn, the valleys not.
  EXPECT_NE(svg.find("ridges\""), std::string::npos);
  EXPECT_EQ(svg.find("valleys\""), std::string::npos);
}
