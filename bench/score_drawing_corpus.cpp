// Scores reliefkit-batch's results on a corpus of real drawings with the checks that need no
// annotation (tests/support/drawing_scores.h) and writes the corpus page (docs/drawing_corpus.md):
// a picture of each drawing beside its result, its figures, pass or fail and the cause.
//
//   score_drawing_corpus --corpus DIR --results DIR --held-out FILE --page FILE.md --pictures DIR
//
// Two pages: FILE.md, the figures alone (the corpus's drawings may not be redistributed: see its
// SOURCES.md), and DIR/../drawing_corpus.md beside the pictures, each drawing beside its result.
// DIR/<kind>/<drawing> are the drawings (kind: pottery -> "Vessel from Profile Drawing", any other
// -> "Relief from Line Drawing"); the results folder holds one reliefkit-batch output per kind
// (RESULTS/<kind>/). FILE lists the held-out drawings, one name a line. Prints one line per drawing
// and the pass counts; exits 0 (the page reports failures, it does not hide them).
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <set>
#include <sstream>

#include "drawing_scores.h"
#include "mesh_files.h"
#include "results.h"

namespace fs = std::filesystem;

namespace {

constexpr double kDefaultPixelMm = 25.4 / 300;  // the drawing filters' defaults: 300 DPI, scale 1
constexpr int kThumbHeight = 180;

struct Entry {
  std::string kind, name;
  bool held_out = false;
  std::string status, error;
  std::vector<std::string> warnings;
  double seconds = 0;
  bool pass = false;
  std::string figures, cause;
};

std::string fixed(double v, int digits) {
  char b[64];
  std::snprintf(b, sizeof b, "%.*f", digits, v);
  return b;
}

std::string pct1(double share) { return fixed(100 * share, 1) + " %"; }

cv::Mat thumb(const cv::Mat& img) {
  cv::Mat out;
  const double s = double(kThumbHeight) / img.rows;
  cv::resize(img, out, cv::Size(std::max(1, int(img.cols * s)), kThumbHeight), 0, 0, cv::INTER_AREA);
  return out;
}

cv::Mat colour_of(const cv::Mat& drawing) {
  cv::Mat c;
  if (drawing.channels() == 1) cv::cvtColor(drawing, c, cv::COLOR_GRAY2BGR);
  else if (drawing.channels() == 4) cv::cvtColor(drawing, c, cv::COLOR_BGRA2BGR);
  else c = drawing.clone();
  if (c.depth() != CV_8U) c.convertTo(c, CV_8U, 1 / 256.0);
  return c;
}

// The relief as a height map: white the paper (within a quarter step of 0), colours by steps.
cv::Mat relief_picture(const cv::Mat& drawing, const reliefkit::TriMesh& m, const std::vector<double>& h, double pixel_mm,
                       double step) {
  cv::Mat levels(drawing.size(), CV_8U, cv::Scalar(0)), mask(drawing.size(), CV_8U, cv::Scalar(0));
  for (const auto& f : m.faces) {
    std::vector<cv::Point> tri;
    double mean = 0;
    for (int k = 0; k < 3; ++k) {
      const auto& v = m.vertices[size_t(f[size_t(k)])];
      tri.emplace_back(int(std::lround(v.x() / pixel_mm)), int(std::lround(-v.y() / pixel_mm)));
      mean += h[size_t(f[size_t(k)])] / 3;
    }
    const int level = mean < -0.25 * step ? 1 : std::clamp(int(std::lround(40 + 50 * mean / step)), 0, 255);
    cv::fillConvexPoly(levels, tri, level);
    cv::fillConvexPoly(mask, tri, std::abs(mean) > 0.25 * step ? 255 : 0);
  }
  cv::Mat coloured;
  cv::applyColorMap(levels, coloured, cv::COLORMAP_TURBO);
  cv::Mat out(drawing.size(), CV_8UC3, cv::Scalar::all(255));
  coloured.copyTo(out, mask);
  cv::Mat ink = colour_of(drawing), grey;
  cv::cvtColor(ink, grey, cv::COLOR_BGR2GRAY);
  cv::Mat dark;
  cv::multiply(out, cv::Scalar::all(0.45), dark);
  dark.copyTo(out, grey < 100);  // the drawing's lines over it, the colour showing through solid ink
  return out;
}

// The vessel's silhouette (its widest radius at each row, both sides of its axis) in red over the
// drawing in grey.
cv::Mat vessel_picture(const cv::Mat& drawing, const reliefkit::TriMesh& m, double pixel_mm) {
  cv::Mat out = colour_of(drawing);
  out = out * 0.45 + cv::Scalar::all(140);
  const rktest::VesselFrame f = rktest::vessel_frame(m, pixel_mm, drawing.rows);  // what the check measures
  const double axis = f.axis_x / pixel_mm;
  const int t = std::max(2, drawing.rows / 150);
  for (size_t row = 0; row < f.radius.size(); ++row)
    for (double side : {-1.0, 1.0})
      if (!std::isnan(f.radius[row]))
        cv::circle(out, cv::Point(int(std::lround(axis + side * f.radius[row])), int(row)), t, cv::Scalar(30, 30, 220), cv::FILLED);
  cv::line(out, cv::Point(int(axis), 0), cv::Point(int(axis), out.rows - 1), cv::Scalar(200, 60, 0), t);
  return out;
}

std::string first_sentence(std::string s) {
  const size_t colon = s.find(": ");
  if (colon != std::string::npos && colon < 60) s = s.substr(colon + 2);  // "filter X: ..." prefix
  if (s.size() > 220) s = s.substr(0, 217) + "...";
  for (char& c : s) if (c == '|' || c == '\n') c = ' ';
  return s;
}

std::string layer_file(const reliefkit::batch::FileResult& r, const std::string& ending) {
  for (const auto& o : r.outputs)
    if (o.file.size() >= ending.size() && o.file.compare(o.file.size() - ending.size(), ending.size(), ending) == 0) return o.file;
  return "";
}

void score_one(Entry& e, const fs::path& drawing_path, const fs::path& results, const fs::path& pictures) {
  reliefkit::batch::FileResult r;
  const fs::path record = reliefkit::batch::result_path(results.string(), e.name);
  if (!reliefkit::batch::read_result(record.string(), r)) {
    e.status = "missing", e.cause = "no result record (" + record.string() + ")";
    return;
  }
  e.status = r.status, e.error = r.error, e.warnings = r.warnings, e.seconds = r.seconds;
  const cv::Mat drawing = cv::imread(drawing_path.string(), cv::IMREAD_UNCHANGED);
  cv::Mat result;
  if (r.status != "ok") {
    e.cause = "refused: " + first_sentence(r.error);
    result = cv::Mat(drawing.size(), CV_8UC3, cv::Scalar(235, 235, 235));
  } else if (e.kind == "pottery") {
    const auto vessel = rktest::read_mesh((results / layer_file(r, "-vessel.ply")).string());
    const rktest::VesselScore s = rktest::score_vessel(drawing, vessel.mesh, kDefaultPixelMm);
    e.pass = s.pass, e.cause = s.cause;
    e.figures = "radius off " + pct1(s.median_error) + " median, " + pct1(s.p90_error) + " 90th pct; covers " +
                pct1(s.coverage) + " of " + std::to_string(s.rows) + " rows; axis " + fixed(s.vessel_axis, 0) +
                " px (drawing's " + fixed(s.drawn_axis, 0) + ")";
    result = vessel_picture(drawing, vessel.mesh, kDefaultPixelMm);
  } else {
    const auto relief = rktest::read_mesh((results / layer_file(r, "-relief.ply")).string());
    const auto& h = relief.vertex_props.at("quality");
    const rktest::ReliefScore s = rktest::score_relief(drawing, relief.mesh, h, kDefaultPixelMm);
    e.pass = s.pass, e.cause = s.cause;
    double lowest = 1;
    for (double share : s.raised) lowest = std::min(lowest, share);
    e.figures = std::to_string(s.objects) + " objects, least raised " + pct1(lowest) + "; paper " + pct1(s.paper_flat) +
                " flat; " + pct1(s.below_paper) + " below it";
    result = relief_picture(drawing, relief.mesh, h, kDefaultPixelMm, s.step);
  }
  cv::Mat side;
  cv::hconcat(std::vector<cv::Mat>{thumb(colour_of(drawing)), cv::Mat(kThumbHeight, 8, CV_8UC3, cv::Scalar::all(255)), thumb(result)}, side);
  cv::imwrite((pictures / (fs::path(e.name).stem().string() + ".png")).string(), side);
}

std::set<std::string> read_names(const fs::path& file) {
  std::set<std::string> names;
  std::ifstream in(file);
  for (std::string line; std::getline(in, line);)
    if (!line.empty() && line[0] != '#') names.insert(line);
  return names;
}

std::string counts(const std::vector<Entry>& all, bool held_out) {
  int n = 0, pass = 0;
  for (const auto& e : all)
    if (e.held_out == held_out) ++n, pass += e.pass;
  return std::to_string(pass) + " of " + std::to_string(n) + " (" + fixed(n ? 100.0 * pass / n : 0, 0) + " %)";
}

void write_page(const fs::path& page, const fs::path& pictures, const std::vector<Entry>& all, bool with_pictures) {
  std::ofstream o(page);
  const fs::path rel = fs::relative(pictures, page.parent_path());
  o << "# The drawing corpus at defaults\n\n"
    << "Made by `scripts/drawing-corpus.sh` (every pottery drawing through \"Vessel from Profile Drawing\", every "
       "other one through \"Relief from Line Drawing\", at their defaults, in reliefkit-batch; scored by "
       "`build/bench/score_drawing_corpus`). The checks need no annotation: see "
       "[drawing_recon.md](drawing_recon.md#the-corpus-checks).\n\n"
    << "**Passing: " << counts(all, false) << " of the tuning part; " << counts(all, true)
    << " of the held-out part** (chosen before any tuning: the first 30 % of each kind by the SHA-1 of the file "
       "name; never tuned on).\n\n";
  if (with_pictures)
    o << "Each picture: the drawing, then the result — a vessel's silhouette in red over the drawing (its axis blue), "
         "a relief's heights in colour under the drawing's lines (white: the paper, flat).\n\n";
  else
    o << "The pictures (each drawing beside its result) are not in the repository: the drawings' terms do not allow "
         "it (../shared/data/drawings/corpus/SOURCES.md). The script draws them into its output folder, with this table "
         "beside them (`build/drawing-corpus/pictures/drawing_corpus.md`).\n\n";
  for (bool held_out : {false, true}) {
    o << (held_out ? "## Held-out part\n\n" : "## Tuning part\n\n");
    o << (with_pictures ? "| drawing | drawing and result | figures | result | cause |\n|---|---|---|---|---|\n"
                        : "| drawing | figures | result | cause |\n|---|---|---|---|\n");
    for (const auto& e : all) {
      if (e.held_out != held_out) continue;
      o << "| " << e.kind << "/" << e.name << " | ";
      if (with_pictures) o << "![](" << (rel / (fs::path(e.name).stem().string() + ".png")).string() << ") | ";
      o << e.figures << (e.seconds > 0 ? "; " + fixed(e.seconds, 1) + " s" : "") << " | " << (e.pass ? "pass" : "**fail**")
        << " | " << e.cause;
      for (const auto& w : e.warnings) o << (e.cause.empty() ? "" : "; ") << "log: " << first_sentence(w);
      o << " |\n";
    }
    o << "\n";
  }
}

}  // namespace

int main(int argc, char** argv) {
  std::map<std::string, std::string> arg;
  for (int i = 1; i + 1 < argc; i += 2) arg[argv[i]] = argv[i + 1];
  for (const char* need : {"--corpus", "--results", "--held-out", "--page", "--pictures"})
    if (!arg.count(need)) {
      std::cerr << "usage: score_drawing_corpus --corpus DIR --results DIR --held-out FILE --page FILE.md --pictures DIR\n";
      return 2;
    }
  const fs::path corpus = arg["--corpus"], results = arg["--results"], pictures = arg["--pictures"];
  const std::set<std::string> held_out = read_names(arg["--held-out"]);
  fs::create_directories(pictures);
  std::vector<Entry> all;
  for (const auto& kind_dir : fs::directory_iterator(corpus)) {
    if (!kind_dir.is_directory()) continue;
    for (const auto& f : fs::directory_iterator(kind_dir)) {
      const std::string ext = f.path().extension().string();
      if (ext != ".png" && ext != ".jpg") continue;
      Entry e;
      e.kind = kind_dir.path().filename().string(), e.name = f.path().filename().string();
      e.held_out = held_out.count(e.name) > 0;
      score_one(e, f.path(), results / e.kind, pictures);
      all.push_back(e);
    }
  }
  std::sort(all.begin(), all.end(), [](const Entry& a, const Entry& b) { return std::tie(a.kind, a.name) < std::tie(b.kind, b.name); });
  for (const auto& e : all)
    std::cout << (e.pass ? "pass " : "FAIL ") << (e.held_out ? "[held-out] " : "") << e.kind << "/" << e.name << ": "
              << e.figures << (e.cause.empty() ? "" : " — " + e.cause) << "\n";
  std::cout << "tuning part: " << counts(all, false) << "; held-out part: " << counts(all, true) << "\n";
  write_page(arg["--page"], pictures, all, false);
  write_page(pictures / "drawing_corpus.md", pictures, all, true);
  return 0;
}
