// ReliefKit — plates of several views at one scale (issue 44): the object's frame from its shape,
// the views of each layout, the panels laid out in a grid. See plate.h.
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>

#include "plate_raster.h"
#include "reliefkit/illustration/plate.h"

namespace reliefkit {
namespace {

constexpr double kGap = 6;        // mm between cells: room for a view's name below it
constexpr double kNameSize = 2.5; // mm

LayoutView view(const std::string& name, const Vec3& direction, const Vec3& up, int column, int row) {
  LayoutView v;
  v.name = name, v.view.direction = direction, v.view.up = up, v.view.name = name, v.column = column, v.row = row;
  return v;
}

// The grid: each column as wide as its widest panel, each row as tall as its tallest, kGap apart.
struct Grid {
  std::vector<double> width, height;
  Vec2 size() const {
    double w = 0, h = 0;
    for (double x : width) w += x;
    for (double y : height) h += y;
    return Vec2(w + kGap * double(std::max<size_t>(width.size(), 1) - 1), h + kGap * double(height.size()));
  }
  Vec2 cell_origin(int column, int row) const {
    Vec2 at(0, 0);
    for (int c = 0; c < column; ++c) at.x() += width[size_t(c)] + kGap;
    for (int r = 0; r < row; ++r) at.y() += height[size_t(r)] + kGap;
    return at;
  }
};

Grid grid_of(const std::vector<PlatePanel>& panels, const std::vector<PageFrame>& real, double ratio) {
  Grid g;
  for (size_t k = 0; k < panels.size(); ++k) {
    const LayoutView& v = panels[k].view;
    if (size_t(v.column) >= g.width.size()) g.width.resize(size_t(v.column) + 1, 0);
    if (size_t(v.row) >= g.height.size()) g.height.resize(size_t(v.row) + 1, 0);
    g.width[size_t(v.column)] = std::max(g.width[size_t(v.column)], real[k].drawing_mm.x() * ratio);
    g.height[size_t(v.row)] = std::max(g.height[size_t(v.row)], real[k].drawing_mm.y() * ratio);
  }
  return g;
}

// The panel's raster copied into the page's at its place (whole pixels: the views line up within one).
void paste(cv::Mat& page, const cv::Mat& panel, const Vec2& at_mm, double px_per_mm) {
  const int x = int(std::lround(at_mm.x() * px_per_mm)), y = int(std::lround(at_mm.y() * px_per_mm));
  const cv::Rect into = cv::Rect(x, y, panel.cols, panel.rows) & cv::Rect(0, 0, page.cols, page.rows);
  if (into.area() > 0) panel(cv::Rect(0, 0, into.width, into.height)).copyTo(page(into));
}

}  // namespace

ObjectFrame object_frame(const TriMesh& mesh, bool turn_over, bool upside_down) {
  const PlateView v = default_view(mesh);  // its direction along the least extent (or the relief's facing side)
  ObjectFrame f;
  f.front = -v.direction.normalized();
  f.up = (v.up - v.up.dot(f.front) * f.front).normalized();
  f.how = "the front " + v.name;
  if (turn_over) f.front = -f.front, f.how += "; turned over";
  if (upside_down) f.up = -f.up, f.how += "; upside down";
  return f;
}

std::vector<LayoutView> layout_views(PlateLayout layout, const ObjectFrame& f) {
  const Vec3 n = f.front, u = f.up, r = u.cross(n);  // r: to the page's right in the front view
  switch (layout) {
    case PlateLayout::one_view:
      return {view("front", -n, u, 0, 0)};
    case PlateLayout::tablet:
      return {view("top edge", -u, -n, 1, 0),   view("left edge", r, u, 0, 1),      view("obverse", -n, u, 1, 1),
              view("right edge", -r, u, 2, 1),  view("bottom edge", u, n, 1, 2),    view("reverse", n, -u, 1, 3)};
    case PlateLayout::lithic:
      return {view("dorsal face", -n, u, 0, 0), view("right profile", -r, u, 1, 0), view("ventral face", n, u, 2, 0)};
    case PlateLayout::two_faces:
      return {view("obverse", -n, u, 0, 0), view("reverse", n, u, 1, 0)};
    case PlateLayout::figurine:
      return {view("front", -n, u, 0, 0), view("right side", r, u, 1, 0), view("back", n, u, 2, 0)};
  }
  return {};
}

Plate make_layout_plate(const TriMesh& mesh, const std::vector<double>& grey, const std::vector<PlateCurves>& layers,
                        PlateLayout layout, const ObjectFrame& frame, const PlateParams& params,
                        const PlateShadingParams* shading) {
  const std::vector<LayoutView> views = layout_views(layout, frame);
  std::vector<std::vector<double>> shaded(views.size());
  if (shading) {
    const Surface surface = Surface::borrow(mesh);
    for (size_t k = 0; k < views.size(); ++k) shaded[k] = plate_shading(surface, views[k].view, *shading);
  }
  std::vector<PlatePanel> panels;
  for (size_t k = 0; k < views.size(); ++k) panels.push_back(PlatePanel{&mesh, shading ? &shaded[k] : &grey, &layers, views[k]});
  return make_panels_plate(panels, params);
}

Plate make_panels_plate(const std::vector<PlatePanel>& panels, const PlateParams& params) {
  if (panels.empty()) throw InputError("A layout needs at least one view.");
  std::vector<PageFrame> real;
  for (const PlatePanel& p : panels) {
    require_triangles(*p.mesh);
    real.push_back(page_frame(*p.mesh, p.view.view, params.unit_mm));
  }
  Plate plate;
  plate.real_size_mm = grid_of(panels, real, 1).size();
  plate.ratio = params.ratio > 0 ? params.ratio : standard_ratio([&](double ratio) { return grid_of(panels, real, ratio).size(); }, params);
  const Grid grid = grid_of(panels, real, plate.ratio);
  PlateParams one = params;
  one.section.axis = SectionAxis::none;
  Plate page = make_plate_page(grid.size(), params);  // the page, its margins and the bar's room
  plate.width_mm = page.width_mm, plate.height_mm = page.height_mm, plate.drawing_origin_mm = page.drawing_origin_mm;
  plate.drawing_size_mm = grid.size();
  const double px_per_mm = params.dpi / 25.4;
  plate.shading = cv::Mat(int(std::ceil(grid.size().y() * px_per_mm)) + 1, int(std::ceil(grid.size().x() * px_per_mm)) + 1, CV_8U,
                          cv::Scalar(255));
  for (size_t k = 0; k < panels.size(); ++k) {
    const PlatePanel& p = panels[k];
    if (params.progress) params.progress(int(100 * k / panels.size()), ("Plate: the " + p.view.name).c_str());
    const PageFrame frame = at_ratio(real[k], plate.ratio);
    const Vec2 cell = grid.cell_origin(p.view.column, p.view.row);
    const Vec2 at = cell + 0.5 * Vec2(grid.width[size_t(p.view.column)] - frame.drawing_mm.x(),
                                      grid.height[size_t(p.view.row)] - frame.drawing_mm.y());
    // Snapped to whole pixels so that the raster and the lines of a view stay together.
    const Vec2 snapped(std::round(at.x() * px_per_mm) / px_per_mm, std::round(at.y() * px_per_mm) / px_per_mm);
    ViewPanel drawn = render_view(*p.mesh, p.grey ? *p.grey : std::vector<double>{}, p.layers ? *p.layers : std::vector<PlateCurves>{},
                                  frame, one);
    paste(plate.shading, drawn.shading, snapped, px_per_mm);
    for (PlatePath& path : drawn.paths) {
      for (Vec2& q : path.points) q += snapped + plate.drawing_origin_mm;
      plate.paths.push_back(std::move(path));
    }
    plate.visible_segments += drawn.visible, plate.hidden_segments += drawn.hidden, plate.outside_segments += drawn.outside;
    const Vec2 below = plate.drawing_origin_mm + cell + Vec2(0.5 * grid.width[size_t(p.view.column)], grid.height[size_t(p.view.row)] + 4);
    plate.texts.push_back(PlateText{below, p.view.name, kNameSize});
  }
  long segments = 0;
  for (const PlatePanel& p : panels)
    for (const auto& l : p.layers ? *p.layers : std::vector<PlateCurves>{}) segments += long(l.segments.size());
  if (segments == 0 && params.curves_required)
    throw InputError("There is no curve to draw: choose a curve layer (Demarcating Curves, Relief Edges, Ridges and "
                     "Valleys...) that holds curves, or run one of those filters first.");
  add_scale_bar(plate, grid.size().y());
  return plate;
}

}  // namespace reliefkit
