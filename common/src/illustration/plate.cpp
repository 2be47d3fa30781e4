// ReliefKit — the illustrator's plate: layout, depth raster, hidden lines, scale bar. See plate.h.
#include "reliefkit/illustration/plate.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <limits>

#include "plate_raster.h"

namespace reliefkit {
namespace {

void check_params(const PlateParams& p, const std::vector<PlateCurves>& layers) {
  auto positive = [](double v) { return std::isfinite(v) && v > 0; };
  if (!positive(p.unit_mm)) throw InputError("The mesh's unit in millimetres must be a positive number.");
  if (!positive(p.ratio) || p.ratio > 1000) throw InputError("The scale must be a positive ratio (1 for 1:1, 2 for 2:1, 0.5 for 1:2).");
  if (!(p.dpi >= 50 && p.dpi <= 2400)) throw InputError("The shading's resolution must be between 50 and 2400 dpi.");
  if (!(p.margin_mm >= 0 && p.margin_mm <= 200)) throw InputError("The margin must be between 0 and 200 mm.");
  if (!(p.hidden_px >= 0 && p.hidden_px <= 100) || !(p.simplify_px >= 0 && p.simplify_px <= 10))
    throw InputError("The hidden-line and simplification tolerances must be small non-negative numbers of pixels.");
  long segments = 0;
  for (const auto& l : layers) segments += long(l.segments.size());
  if (segments == 0)
    throw InputError("There is no curve to draw: choose a curve layer (Demarcating Curves, Relief Edges, Ridges and "
                     "Valleys...) that holds curves, or run one of those filters first.");
}

// The page: the drawing at its scale, the margins, the scale bar's room below; a fixed page when asked.
void lay_out(Plate& plate, const Vec2& drawing_mm, const PlateParams& p) {
  constexpr double kBarRoom = 12;  // below the drawing: the bar, its label and the scale
  plate.drawing_size_mm = drawing_mm;
  const double need_w = drawing_mm.x() + 2 * p.margin_mm, need_h = drawing_mm.y() + 2 * p.margin_mm + kBarRoom;
  plate.width_mm = p.page_width_mm > 0 ? p.page_width_mm : need_w;
  plate.height_mm = p.page_height_mm > 0 ? p.page_height_mm : need_h;
  if (plate.width_mm + 1e-9 < need_w || plate.height_mm + 1e-9 < need_h) {
    char msg[300];
    std::snprintf(msg, sizeof msg,
                  "At this scale the drawing is %.0f x %.0f mm and needs a page of %.0f x %.0f mm with its margins and "
                  "scale bar; the page is %.0f x %.0f mm. Choose a smaller scale or a larger page.",
                  drawing_mm.x(), drawing_mm.y(), need_w, need_h, plate.width_mm, plate.height_mm);
    throw InputError(msg);
  }
  plate.drawing_origin_mm = Vec2(0.5 * (plate.width_mm - drawing_mm.x()), 0.5 * (plate.height_mm - kBarRoom - drawing_mm.y()));
}

// A round real length (1, 2 or 5 times a power of ten, in mm), the nearest (by ratio) to a quarter
// of the drawing's width.
void add_scale_bar(Plate& plate, const PlateParams& p) {
  const double target_real = 0.25 * plate.drawing_size_mm.x() / p.ratio;
  const double decade = std::pow(10.0, std::floor(std::log10(std::max(target_real, 1e-9))));
  double real = decade;
  for (double m : {2.0, 5.0, 10.0})
    if (std::abs(std::log(m * decade / target_real)) < std::abs(std::log(real / target_real))) real = m * decade;
  plate.bar_length_mm = real * p.ratio;
  plate.bar_start_mm = plate.drawing_origin_mm + Vec2(0, plate.drawing_size_mm.y() + 4);
  char text[64];
  std::snprintf(text, sizeof text, "%g mm", real);
  plate.bar_label = text;
  if (p.ratio >= 1) std::snprintf(text, sizeof text, "%g:1", p.ratio);
  else std::snprintf(text, sizeof text, "1:%g", 1 / p.ratio);
  plate.scale_label = text;
}
}  // namespace

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
  return view;
}

Plate make_plate(const TriMesh& mesh, const std::vector<double>& grey, const std::vector<PlateCurves>& layers,
                 const PlateView& view, const PlateParams& params) {
  require_triangles(mesh);
  check_params(params, layers);
  if (!grey.empty() && grey.size() != mesh.vertices.size()) throw InputError("The shading has not one value per vertex.");
  const PageFrame frame = page_frame(mesh, view, params);
  Plate plate;
  lay_out(plate, frame.drawing_mm, params);
  const DepthRaster raster = rasterize(mesh, grey, frame, params);
  plate.shading = raster.grey;
  for (const auto& layer : layers) add_visible_paths(plate, layer, frame, raster, params);
  for (auto& path : plate.paths)
    for (auto& q : path.points) q += plate.drawing_origin_mm;
  add_scale_bar(plate, params);
  return plate;
}

}  // namespace reliefkit
