// reliefkit-batch (batch/): the real program in the private prefix, MeshLab 2020.09's plugins and
// ours, over small collections: a folder with a file MeshLab cannot read, resume, shards and
// their merge, Slurm's array variables, a filter script, the memory cap, a folder of drawings.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "mesh_files.h"
#include "server.h"
#include "shapes.h"

namespace fs = std::filesystem;

namespace {

struct BatchRun {
  int status = -1;
  std::string output;
};

// Runs build/prefix/bin/reliefkit-batch with `args` (and environment assignments `env`, "K=V").
BatchRun batch(const std::vector<std::string>& args, const std::vector<std::string>& env = {}) {
  std::string cmd = "env -u DISPLAY";
  for (const auto& e : env) cmd += " '" + e + "'";
  cmd += " OMP_WAIT_POLICY=PASSIVE " + rktest::binary_dir() + "/prefix/bin/reliefkit-batch";
  for (const auto& a : args) cmd += " '" + a + "'";
  cmd += " 2>&1";
  BatchRun r;
  FILE* p = popen(cmd.c_str(), "r");
  char buf[4096];
  size_t n;
  while ((n = fread(buf, 1, sizeof buf, p)) > 0) r.output.append(buf, n);
  const int s = pclose(p);
  r.status = WIFEXITED(s) ? WEXITSTATUS(s) : -1;
  return r;
}

std::string read_text(const fs::path& p) {
  std::ifstream f(p);
  std::stringstream s;
  s << f.rdbuf();
  return s.str();
}

int count_lines_starting(const std::string& text, const std::string& prefix) {
  int n = 0;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) n += line.rfind(prefix, 0) == 0;
  return n;
}

// scans/a/sphere.ply, scans/b/torus.ply, scans/broken.ply (not a PLY).
std::string make_scans(const std::string& dir) {
  const fs::path scans = fs::path(dir) / "scans";
  fs::create_directories(scans / "a");
  fs::create_directories(scans / "b");
  rktest::write_ply((scans / "a/sphere.ply").string(), rktest::sphere(1.0, 4, 0.2));
  rktest::write_ply((scans / "b/torus.ply").string(), rktest::torus(2.0, 0.7, 90, 36, 0.2));
  std::ofstream(scans / "broken.ply") << "ply\nformat ascii 1.0\nelement vertex 3\nend_header\nnot numbers\n";
  return scans.string();
}
}  // namespace

TEST(BatchTool, AFolderIsProcessedAndABrokenFileStopsOnlyItself) {
  const std::string dir = rktest::temp_dir("batch_folder");
  const std::string scans = make_scans(dir), out = dir + "/out";
  const BatchRun r = batch({"--filter", "Demarcating Curves", "--param", "threshold=0.3", "--jobs", "2", scans, out});
  std::printf("%s\n", r.output.c_str());
  EXPECT_EQ(r.status, 1);  // one file failed
  EXPECT_NE(r.output.find("3 files in"), std::string::npos);
  EXPECT_NE(r.output.find("[1/3 a/sphere.ply] started"), std::string::npos);
  EXPECT_NE(r.output.find("Demarcating Curves: "), std::string::npos);  // the filter's progress
  EXPECT_NE(r.output.find("2 ok, 1 failed, 0 crashed, 0 memory"), std::string::npos);
  const std::string csv = read_text(out + "/summary.csv");
  EXPECT_EQ(count_lines_starting(csv, "a/sphere.ply,ok,"), 1) << csv;
  EXPECT_EQ(count_lines_starting(csv, "b/torus.ply,ok,"), 1) << csv;
  EXPECT_EQ(count_lines_starting(csv, "broken.ply,failed,"), 1) << csv;
  EXPECT_NE(csv.find("could not read"), std::string::npos) << csv;
  // The torus's layers: the mesh (PLY) and its curves as an OBJ with its edges.
  const std::string curves = read_text(out + "/b/torus/torus-demarcating_curves.obj");
  EXPECT_GE(count_lines_starting(curves, "l "), 20) << "edges kept (measured 37, the segments the log counts)";
  // The sphere has no curve above the threshold: its empty layer is not written, and said so.
  EXPECT_FALSE(fs::exists(out + "/a/sphere/sphere-demarcating_curves.obj"));
  EXPECT_NE(csv.find("layer \"\"sphere – demarcating curves\"\" is empty: not written"), std::string::npos) << csv;
  EXPECT_TRUE(fs::exists(out + "/b/torus/torus.ply"));
  EXPECT_NE(read_text(out + "/summary.json").find("\"failed\": 1"), std::string::npos);
}

TEST(BatchTool, AResumedRunSkipsWhatIsDone) {
  const std::string dir = rktest::temp_dir("batch_resume");
  const std::string scans = make_scans(dir), out = dir + "/out";
  batch({"--filter", "Compute Curvature Tensor and Derivatives", scans, out});
  const auto written = fs::last_write_time(out + "/a/sphere/sphere.ply");
  // Interrupted while the torus was handled: its record is missing.
  fs::remove(out + "/.reliefkit-batch/results/b/torus.ply.json");
  const BatchRun again = batch({"--filter", "Compute Curvature Tensor and Derivatives", scans, out});
  EXPECT_NE(again.output.find("shard 0/1: 3, 2 done before, 1 to do"), std::string::npos) << again.output;
  EXPECT_EQ(fs::last_write_time(out + "/a/sphere/sphere.ply"), written);
  EXPECT_NE(again.output.find("2 ok, 1 failed"), std::string::npos) << again.output;
  const BatchRun retry = batch({"--filter", "Compute Curvature Tensor and Derivatives", "--retry-failed", scans, out});
  EXPECT_NE(retry.output.find("3, 2 done before, 1 to do"), std::string::npos) << retry.output;
}

TEST(BatchTool, ShardsFromSlurmsArrayAreMergedByOneCommand) {
  const std::string dir = rktest::temp_dir("batch_shards");
  const std::string scans = make_scans(dir), out = dir + "/out";
  const auto slurm = [](int id) {
    return std::vector<std::string>{"SLURM_ARRAY_TASK_ID=" + std::to_string(id), "SLURM_ARRAY_TASK_COUNT=2",
                                    "SLURM_ARRAY_TASK_MIN=1", "SLURM_ARRAY_TASK_MAX=2"};
  };
  const BatchRun first = batch({"--filter", "Curvature Shading", scans, out}, slurm(1));
  const BatchRun second = batch({"--filter", "Curvature Shading", scans, out}, slurm(2));
  EXPECT_NE(first.output.find("shard 0/2: 2,"), std::string::npos) << first.output;  // a/sphere.ply and broken.ply
  EXPECT_NE(second.output.find("shard 1/2: 1,"), std::string::npos) << second.output;
  EXPECT_TRUE(fs::exists(out + "/summary-shard-0-of-2.csv"));
  EXPECT_TRUE(fs::exists(out + "/summary-shard-1-of-2.csv"));
  const BatchRun merged = batch({"merge", out});
  EXPECT_NE(merged.output.find("3 files: 2 ok, 1 failed"), std::string::npos) << merged.output;
  EXPECT_EQ(count_lines_starting(read_text(out + "/summary.csv"), "b/torus.ply,ok,"), 1);
  // --shard wins over the environment; a bad shard is a usage error.
  EXPECT_NE(batch({"--filter", "Curvature Shading", "--shard", "1/2", scans, dir + "/o2"}, slurm(1)).output.find("shard 1/2"),
            std::string::npos);
  EXPECT_EQ(batch({"--filter", "Curvature Shading", "--shard", "2/2", scans, dir + "/o3"}).status, 2);
}

TEST(BatchTool, AScriptAndTheMemoryCap) {
  const std::string dir = rktest::temp_dir("batch_script");
  const std::string scans = make_scans(dir), out = dir + "/out";
  const std::string script = dir + "/shade.mlx";
  std::ofstream(script) << "<!DOCTYPE FilterScript>\n<FilterScript>\n"
                        << rktest::mlx_filter("Curvature Shading", {rktest::param_float("contrast", 2.0)})
                        << rktest::mlx_filter("Demarcating Curves", {rktest::param_float("threshold", 0.3)})
                        << "</FilterScript>\n";
  const BatchRun r = batch({"--script", script, "--save", "new", "--extensions", "ply", scans + "/b", out});
  EXPECT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("Curvature Shading: "), std::string::npos);
  EXPECT_TRUE(fs::exists(out + "/torus/torus-demarcating_curves.obj"));
  EXPECT_FALSE(fs::exists(out + "/torus/torus.ply"));  // --save new: only the layers the filters added
  // A cap below what MeshLab needs to start: every file stopped and recorded, the run ends.
  const BatchRun capped = batch({"--filter", "Curvature Shading", "--memory-cap", "40M", scans + "/b", dir + "/capped"});
  EXPECT_EQ(capped.status, 1);
  EXPECT_NE(capped.output.find("0 ok, 0 failed, 0 crashed, 1 memory"), std::string::npos) << capped.output;
  EXPECT_NE(capped.output.find("over its share of the memory cap"), std::string::npos);
}

TEST(BatchTool, DrawingsTakeTheirPathFromInput) {
  const std::string dir = rktest::temp_dir("batch_drawings");
  fs::create_directories(dir + "/drawings");
  fs::copy_file(rktest::source_dir() + "/examples/data/nested_drawing.png", dir + "/drawings/nested.png");
  const BatchRun r = batch({"--filter", "Line Drawing to Curves", "--param", "drawing={input}", "--extensions", "png",
                       dir + "/drawings", dir + "/out"});
  EXPECT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("1 ok"), std::string::npos) << r.output;
  bool curves = false;
  for (const auto& e : fs::recursive_directory_iterator(dir + "/out/nested"))
    curves = curves || (e.path().extension() == ".obj" && count_lines_starting(read_text(e.path()), "l ") > 10);
  EXPECT_TRUE(curves) << "the drawing's curves written as an OBJ with edges";
}

TEST(BatchTool, UsageErrors) {
  const std::string dir = rktest::temp_dir("batch_usage");
  const std::string scans = make_scans(dir);
  EXPECT_EQ(batch({scans, dir + "/out"}).status, 2);                                   // nothing to apply
  EXPECT_EQ(batch({"--filter", "X", "--script", "y.mlx", scans, dir + "/out"}).status, 2);  // both
  EXPECT_EQ(batch({"--filter", "Curvature Shading", "--jobs", "0", scans, dir + "/out"}).status, 2);
  EXPECT_EQ(batch({"--filter", "Curvature Shading", dir + "/missing", dir + "/out"}).status, 2);
  const BatchRun unknown = batch({"--filter", "No Such Filter", scans + "/a", dir + "/out"});
  EXPECT_EQ(unknown.status, 1);
  EXPECT_NE(unknown.output.find("no filter is called \"No Such Filter\""), std::string::npos) << unknown.output;
  const BatchRun bad_param = batch({"--filter", "Demarcating Curves", "-p", "threshold=abc", scans + "/a", dir + "/out2"});
  EXPECT_NE(bad_param.output.find("\"abc\" is not a"), std::string::npos) << bad_param.output;
}

TEST(BatchTool, APlateForEveryScan) {
  // "{output}" in a file parameter is the file's output folder: one plate (SVG and PDF) per scan.
  const std::string dir = rktest::temp_dir("batch_plates");
  const std::string scans = make_scans(dir), out = dir + "/out";
  const std::string script = dir + "/plate.mlx";
  std::ofstream(script) << "<!DOCTYPE FilterScript>\n<FilterScript>\n"
                        << rktest::mlx_filter("Demarcating Curves", {rktest::param_float("threshold", 0.3)})
                        << rktest::mlx_filter("Export Illustration Plate", {rktest::param_save_file("file", "{output}/plate.svg", "*.svg")})
                        << "</FilterScript>\n";
  const BatchRun r = batch({"--script", script, "--save", "none", scans + "/b", out});
  EXPECT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("Illustration plate: "), std::string::npos) << r.output;
  EXPECT_NE(read_text(out + "/torus/plate.svg").find("<path"), std::string::npos);
  EXPECT_TRUE(fs::exists(out + "/torus/plate.pdf"));
  // The default file, "beside the mesh's file", is in the file's outputs folder: the collection
  // is left as it was.
  const std::string default_script = dir + "/default.mlx";
  std::ofstream(default_script) << "<!DOCTYPE FilterScript>\n<FilterScript>\n"
                                << rktest::mlx_filter("Demarcating Curves", {rktest::param_float("threshold", 0.3)})
                                << rktest::mlx_filter("Export Illustration Plate", {}) << "</FilterScript>\n";
  const BatchRun d = batch({"--script", default_script, "--save", "none", scans + "/b", dir + "/out2"});
  EXPECT_EQ(d.status, 0) << d.output;
  EXPECT_TRUE(fs::exists(dir + "/out2/torus/torus-plate.svg")) << d.output;
  EXPECT_FALSE(fs::exists(scans + "/b/torus-plate.svg"));
  // A relief a filter made from a drawing has no file of its own: its plate goes to the outputs
  // folder too.
  fs::create_directories(dir + "/drawings");
  fs::copy_file(rktest::source_dir() + "/examples/data/nested_drawing.png", dir + "/drawings/nested.png");
  const std::string relief_script = dir + "/relief.mlx";
  std::ofstream(relief_script) << "<!DOCTYPE FilterScript>\n<FilterScript>\n"
                               << rktest::mlx_filter("Relief from Line Drawing", {rktest::param_file("drawing", "{input}")})
                               << rktest::mlx_filter("Export Illustration Plate", {}) << "</FilterScript>\n";
  const BatchRun rel = batch({"--script", relief_script, "--save", "none", "--extensions", "png", dir + "/drawings", dir + "/out3"});
  EXPECT_EQ(rel.status, 0) << rel.output;
  int plates = 0;
  for (const auto& e : fs::directory_iterator(dir + "/out3/nested")) plates += e.path().extension() == ".svg";
  EXPECT_EQ(plates, 1) << rel.output;
  // The relief's interpretation file, written beside its drawing in MeshLab, is an output here.
  EXPECT_TRUE(fs::exists(dir + "/out3/nested/nested.interpretation.json"));
  EXPECT_FALSE(fs::exists(dir + "/drawings/nested.interpretation.json"));
}

TEST(BatchTool, AnObjMeshLabsImporterStopsOnSaysWhatToDo) {
  // MeshLab 2020.09's OBJ importer fails an assertion on an OBJ ending in blank lines (as the
  // shared fertility.obj does): the file is recorded crashed, with the conversion to PLY to make.
  const std::string dir = rktest::temp_dir("batch_obj");
  fs::create_directories(dir + "/scans");
  std::ofstream(dir + "/scans/blank_lines.obj") << "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nf 1 2 3\nf 2 4 3\n\n\n";
  const BatchRun r = batch({"--filter", "Demarcating Curves", dir + "/scans", dir + "/out"});
  EXPECT_EQ(r.status, 1) << r.output;
  EXPECT_NE(r.output.find("0 ok, 0 failed, 1 crashed"), std::string::npos) << r.output;
  EXPECT_NE(read_text(dir + "/out/summary.csv").find("convert it to PLY"), std::string::npos) << r.output;
}
