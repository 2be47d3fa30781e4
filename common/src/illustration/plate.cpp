// ReliefKit — the illustrator's plate: layout, depth raster, hidden lines, scale bar. See plate.h.
#include "reliefkit/illustration/plate.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>

#include "plate_raster.h"

namespace reliefkit {
namespace {

void check_params(const PlateParams& p, const std::vector<PlateCurves>& layers) {
  auto positive = [](double v) { return std::isfinite(v) && v > 0; };
  if (!positive(p.unit_mm)) throw InputError("The mesh's unit in millimetres must be a positive number.");
  if (!(p.ratio == 0 || positive(p.ratio)) || p.ratio > 1000)
    throw InputError("The scale must be a positive ratio (1 for 1:1, 2 for 2:1, 0.5 for 1:2) or 0 (automatic).");
  if (!(p.dpi >= 50 && p.dpi <= 2400)) throw InputError("The shading's resolution must be between 50 and 2400 dpi.");
  if (!(p.margin_mm >= 0 && p.margin_mm <= 200)) throw InputError("The margin must be between 0 and 200 mm.");
  if (!(p.hidden_px >= 0 && p.hidden_px <= 100) || !(p.simplify_px >= 0 && p.simplify_px <= 10))
    throw InputError("The hidden-line and simplification tolerances must be small non-negative numbers of pixels.");
  if (!(p.section.at >= 0 && p.section.at <= 1)) throw InputError("The section's place must be a fraction between 0 and 1.");
  long segments = 0;
  for (const auto& l : layers) segments += long(l.segments.size());
  if (segments == 0 && p.curves_required)
    throw InputError("There is no curve to draw: choose a curve layer (Demarcating Curves, Relief Edges, Ridges and "
                     "Valleys...) that holds curves, or run one of those filters first.");
}

constexpr double kBarRoom = 12;         // below the drawing: the bar, its label and the scale beside it
constexpr double kBarLeastWidth = 32;   // the bar (at most 0.4 of the width) and the scale beside it
constexpr double kTitleLine = 4;        // a title's line above the drawing

// The titles' room above the drawing and their width (DejaVu Sans: about 0.55 of the size per character).
double title_room(const PlateParams& p) { return kTitleLine * double(p.titles.size()); }
double title_width(const PlateParams& p) {
  double w = 0;
  for (size_t k = 0; k < p.titles.size(); ++k) w = std::max(w, 0.55 * (k == 0 ? 3.0 : 2.5) * double(p.titles[k].size()));
  return w;
}


// What the page holds besides its margins and the bar: the drawing and its section's profile.
Vec2 content_mm(const PageFrame& frame, const PlateParams& p) { return frame.drawing_mm + section_room_mm(frame, p); }

// The standard scale of archaeological drawing (drawn : real), the largest at which the content
// fits the page — A4, portrait or landscape, when the page fits the drawing.
double automatic_ratio(const PageFrame& real, const PlateParams& p) {
  return standard_ratio([&](double ratio) { return content_mm(at_ratio(real, ratio), p); }, p);
}

// The page: the content at its scale, the margins, the scale bar's room below; a fixed page when asked.
void lay_out(Plate& plate, const Vec2& drawing_mm, const Vec2& content, const PlateParams& p) {
  plate.drawing_size_mm = drawing_mm;
  const double need_w = std::max({content.x(), kBarLeastWidth, title_width(p)}) + 2 * p.margin_mm,
               need_h = content.y() + 2 * p.margin_mm + kBarRoom + title_room(p);
  plate.width_mm = p.page_width_mm > 0 ? p.page_width_mm : need_w;
  plate.height_mm = p.page_height_mm > 0 ? p.page_height_mm : need_h;
  if (plate.width_mm + 1e-9 < need_w || plate.height_mm + 1e-9 < need_h) {
    char msg[300];
    std::snprintf(msg, sizeof msg,
                  "At this scale the drawing is %.0f x %.0f mm and needs a page of %.0f x %.0f mm with its margins and "
                  "scale bar; the page is %.0f x %.0f mm. Choose a smaller scale or a larger page.",
                  content.x(), content.y(), need_w, need_h, plate.width_mm, plate.height_mm);
    throw InputError(msg);
  }
  plate.drawing_origin_mm =
      Vec2(0.5 * (plate.width_mm - content.x()), 0.5 * (plate.height_mm - kBarRoom - content.y() + title_room(p)));
}

// A plate without lines is no plate: say why.
void check_drawn(const Plate& plate, const PlateParams& p) {
  if (plate.visible_segments > 0 || (!p.curves_required && plate.hidden_segments == 0)) return;
  if (plate.hidden_segments == 0)
    throw InputError("The curves lie off the mesh's drawing: they are not this mesh's curves. Make the mesh they were "
                     "found on current, or name its curve layers.");
  throw InputError("Every curve is hidden behind the surface from this view: choose another view (Facing the relief, or "
                   "the direction the curves are seen from).");
}

// The guides (a rollout's seam) dash-dot in the light pen over everything; the titles above the
// drawing, the first larger, in the top margin.
void add_guides_and_titles(Plate& plate, const PageFrame& frame, const PlateParams& p) {
  for (const auto& line : p.guides) {
    PlatePath path{{}, 0.25, "guides", true, false};
    for (const Vec3& q : line) path.points.push_back(frame.to_mm(q) + plate.drawing_origin_mm);
    if (path.points.size() >= 2) plate.paths.push_back(std::move(path));
  }
  const double x = plate.drawing_origin_mm.x() + 0.5 * plate.drawing_size_mm.x();
  double y = plate.drawing_origin_mm.y() - 2 - kTitleLine * double(std::max<size_t>(p.titles.size(), 1) - 1);
  for (size_t k = 0; k < p.titles.size(); ++k, y += kTitleLine) plate.texts.push_back(PlateText{Vec2(x, y), p.titles[k], k == 0 ? 3.0 : 2.5});
}
}  // namespace

// A round real length (1, 2 or 5 times a power of ten, in mm), the nearest (by ratio) to a quarter
// of the drawing's width, below the content.
void add_scale_bar(Plate& plate, double content_height_mm) {
  const double target_real = 0.25 * plate.drawing_size_mm.x() / plate.ratio;
  const double decade = std::pow(10.0, std::floor(std::log10(std::max(target_real, 1e-9))));
  double real = decade;
  for (double m : {2.0, 5.0, 10.0})
    if (std::abs(std::log(m * decade / target_real)) < std::abs(std::log(real / target_real))) real = m * decade;
  plate.bar_length_mm = real * plate.ratio;
  plate.bar_start_mm = plate.drawing_origin_mm + Vec2(0, content_height_mm + 4);
  char text[64];
  std::snprintf(text, sizeof text, "%g mm", real);
  plate.bar_label = text;
  if (plate.ratio >= 1) std::snprintf(text, sizeof text, "%g:1", plate.ratio);
  else std::snprintf(text, sizeof text, "1:%g", 1 / plate.ratio);
  plate.scale_label = text;
}

ViewPanel render_view(const TriMesh& mesh, const std::vector<double>& grey, const std::vector<PlateCurves>& layers,
                      const PageFrame& frame, const PlateParams& params, double outline_mm) {
  const DepthRaster raster = rasterize(mesh, grey, frame, params);
  Plate scratch;  // add_visible_paths counts into a plate
  if (outline_mm > 0)
    for (std::vector<Vec2>& line : silhouette_outline(raster, params.simplify_px))
      scratch.paths.push_back(PlatePath{std::move(line), outline_mm, "outline"});
  for (size_t k = 0; k < layers.size(); ++k) add_visible_paths(scratch, layers[k], int(k), frame, raster, params);
  ViewPanel panel;
  panel.shading = raster.grey;
  panel.size_mm = frame.drawing_mm;
  panel.paths = std::move(scratch.paths);
  panel.visible = scratch.visible_segments, panel.hidden = scratch.hidden_segments, panel.outside = scratch.outside_segments;
  return panel;
}

Plate make_plate_page(const Vec2& content_mm, const PlateParams& params) {
  PlateParams checked = params;
  checked.curves_required = false;
  check_params(checked, {});
  Plate page;
  lay_out(page, content_mm, content_mm, params);
  return page;
}

PageFrame at_ratio(PageFrame frame, double ratio) {
  frame.mm_per_unit *= ratio;
  frame.drawing_mm *= ratio;
  return frame;
}

double standard_ratio(const std::function<Vec2(double)>& content_at, const PlateParams& p) {
  static const double kScales[] = {1000, 500, 200, 100, 50, 20, 10, 5, 4, 3, 2, 1, 1 / 2., 1 / 3., 1 / 4., 1 / 5., 1 / 10., 1 / 20., 1 / 50.,
                                   1 / 100., 1 / 200., 1 / 500., 1 / 1000.};
  std::vector<Vec2> pages{Vec2(p.page_width_mm, p.page_height_mm)};
  if (p.page_width_mm <= 0 || p.page_height_mm <= 0) pages = {Vec2(210, 297), Vec2(297, 210)};
  for (const Vec2& page : pages)
    if (page.x() <= 2 * p.margin_mm || page.y() <= 2 * p.margin_mm + kBarRoom)
      throw InputError("The page is too small for its margins and the scale bar.");
  for (double ratio : kScales)
    for (const Vec2& page : pages) {
      const Vec2 room = page - Vec2(2 * p.margin_mm, 2 * p.margin_mm + kBarRoom + title_room(p)), need = content_at(ratio);
      if (need.x() <= room.x() && need.y() <= room.y()) return ratio;
    }
  char msg[300];
  std::snprintf(msg, sizeof msg, "The object is %.0f x %.0f mm at the mesh unit given (%g mm): too large for the page even at "
                "1:1000. Check the mesh unit.", content_at(1).x(), content_at(1).y(), p.unit_mm);
  throw InputError(msg);
}

PlateView facing_view(const TriMesh& mesh) {
  if (mesh.vertices.empty()) throw InputError("The mesh is empty: there is nothing to draw.");
  Vec3 mean = Vec3::Zero();
  for (const auto& v : mesh.vertices) mean += v;
  mean /= double(mesh.vertices.size());
  Mat3 cov = Mat3::Zero();
  for (const auto& v : mesh.vertices) cov += (v - mean) * (v - mean).transpose();
  const Eigen::SelfAdjointEigenSolver<Mat3> eig(cov);  // eigenvalues ascending
  PlateView view;
  view.direction = eig.eigenvectors().col(0);
  double facing = 0;
  for (const auto& f : mesh.faces)
    facing += (mesh.vertices[size_t(f[1])] - mesh.vertices[size_t(f[0])])
                  .cross(mesh.vertices[size_t(f[2])] - mesh.vertices[size_t(f[0])])
                  .dot(view.direction);
  if (facing > 0) view.direction = -view.direction;  // look at the side the normals face
  // Up as the scan was made: its y axis (MeshLab's default view), or its z axis when the view runs
  // along y — not the axis of largest extent, which on a round coin is any diameter.
  view.up = std::abs(view.direction.y()) < 0.9 ? Vec3(0, 1, 0) : Vec3(0, 0, 1);
  view.name = "facing the relief";
  return view;
}

Eigen::SelfAdjointEigenSolver<Mat3> surface_axes(const TriMesh& mesh) {
  Vec3 mean = Vec3::Zero();
  double total = 0;
  std::vector<std::pair<Vec3, double>> centroids;
  centroids.reserve(mesh.faces.size());
  for (const auto& f : mesh.faces) {
    const Vec3 &a = mesh.vertices[size_t(f[0])], &b = mesh.vertices[size_t(f[1])], &c = mesh.vertices[size_t(f[2])];
    const double area = 0.5 * (b - a).cross(c - a).norm();
    centroids.emplace_back((a + b + c) / 3, area);
    mean += area * centroids.back().first, total += area;
  }
  if (!(total > 0)) throw InputError("The mesh has no surface to draw (no face with an area).");
  mean /= total;
  Mat3 cov = Mat3::Zero();
  for (const auto& [q, area] : centroids) cov += area * (q - mean) * (q - mean).transpose();
  return Eigen::SelfAdjointEigenSolver<Mat3>(cov / total);
}

namespace {
// The first of the components (z, x, y) that is not near zero made negative: looking the way
// MeshLab's first view looks (along -z), else from +x, else from +y.
Vec3 as_meshlab_looks(Vec3 d) {
  for (int axis : {2, 0, 1})
    if (std::abs(d[axis]) >= 0.1) return d[axis] > 0 ? Vec3(-d) : d;
  return d;
}
}  // namespace

// The scan's y stays up unless the object's largest extent lies more than this many degrees from it
// (a scan lying on its side). Chosen on the shared objects: the torso 2, the gargoyle 18, the bunny
// 42, the fertility statue 61 degrees — all upright as scanned; their largest extent up put the
// bunny and the statue (wider than tall) on a slant.
constexpr int kScanUpKeptDeg = 70;

PlateView default_view(const TriMesh& mesh) {
  if (mesh.vertices.empty()) throw InputError("The mesh is empty: there is nothing to draw.");
  const auto axes = surface_axes(mesh);
  const Vec3 extent = axes.eigenvalues().cwiseMax(0).cwiseSqrt();  // ascending
  if (extent[0] < 0.35 * extent[1]) {
    PlateView v = facing_view(mesh);
    v.name = "facing the relief (its least extent " + std::to_string(int(std::lround(100 * extent[0] / std::max(extent[1], 1e-300)))) +
             " % of its middle one)";
    return v;
  }
  PlateView v;
  v.direction = as_meshlab_looks(axes.eigenvectors().col(0));
  const Vec3 longest = axes.eigenvectors().col(2);
  const int off_y = int(std::lround(std::acos(std::min(1.0, std::abs(longest.y()))) * 180 / M_PI));
  if (off_y <= kScanUpKeptDeg) {
    v.up = Vec3::UnitY();
    v.name = "upright as scanned (its largest extent " + std::to_string(off_y) + " degrees from the scan's y), facing its widest side";
  } else {
    v.up = std::abs(longest.y()) >= 0.1 ? (longest.y() > 0 ? longest : Vec3(-longest)) : (longest.z() >= 0 ? longest : Vec3(-longest));
    v.name = "upright (its largest extent up the page, " + std::to_string(off_y) + " degrees from the scan's y), facing its widest side";
  }
  return v;
}

Plate make_plate(const TriMesh& mesh, const std::vector<double>& grey, const std::vector<PlateCurves>& layers,
                 const PlateView& view, const PlateParams& params) {
  require_triangles(mesh);
  check_params(params, layers);
  if (!grey.empty() && grey.size() != mesh.vertices.size()) throw InputError("The shading has not one value per vertex.");
  const PageFrame real = page_frame(mesh, view, params.unit_mm);
  Plate plate;
  plate.real_size_mm = real.drawing_mm;
  plate.ratio = params.ratio > 0 ? params.ratio : automatic_ratio(real, params);
  const PageFrame frame = at_ratio(real, plate.ratio);
  lay_out(plate, frame.drawing_mm, content_mm(frame, params), params);
  if (params.progress) params.progress(5, "Plate: the surface's depth, its shading and the hidden lines");
  ViewPanel panel = render_view(mesh, grey, layers, frame, params);
  plate.shading = panel.shading;
  plate.paths = std::move(panel.paths);
  plate.visible_segments = panel.visible, plate.hidden_segments = panel.hidden, plate.outside_segments = panel.outside;
  check_drawn(plate, params);
  for (auto& path : plate.paths)
    for (auto& q : path.points) q += plate.drawing_origin_mm;
  add_guides_and_titles(plate, frame, params);
  if (params.progress) params.progress(80, "Plate: the section");
  add_section(plate, mesh, frame, params);
  add_scale_bar(plate, content_mm(frame, params).y());
  return plate;
}

}  // namespace reliefkit
