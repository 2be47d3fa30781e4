// ReliefKit — plates of several views at one scale (issue 44): the object's frame from its shape,
// the views of each layout, the panels laid out in a grid. See plate.h.
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <cstdio>

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

// The section's cell (issue 44: a tool's sections): the first view's profile in a row below the
// grid, under that view (horizontal), or a column right of it, beside it (vertical).
struct SectionCell {
  int column = -1, row = -1;  // none
  Vec2 size_mm{0, 0};
};

SectionCell section_cell(const std::vector<PlatePanel>& panels, const PageFrame& first, const PlateParams& params, double ratio) {
  SectionCell cell;
  if (params.section.axis == SectionAxis::none) return cell;
  int columns = 0, rows = 0;
  for (const PlatePanel& p : panels) columns = std::max(columns, p.view.column + 1), rows = std::max(rows, p.view.row + 1);
  const PageFrame at = at_ratio(first, ratio);
  const double depth_mm = (at.farthest - at.nearest) * at.mm_per_unit;
  if (params.section.axis == SectionAxis::horizontal)
    cell.column = panels[0].view.column, cell.row = rows, cell.size_mm = Vec2(at.drawing_mm.x(), depth_mm);
  else
    cell.column = columns, cell.row = panels[0].view.row, cell.size_mm = Vec2(depth_mm, at.drawing_mm.y());
  return cell;
}

Grid grid_of(const std::vector<PlatePanel>& panels, const std::vector<PageFrame>& real, double ratio, const PlateParams& params) {
  Grid g;
  auto widen = [&](int column, int row, const Vec2& size) {
    if (size_t(column) >= g.width.size()) g.width.resize(size_t(column) + 1, 0);
    if (size_t(row) >= g.height.size()) g.height.resize(size_t(row) + 1, 0);
    g.width[size_t(column)] = std::max(g.width[size_t(column)], size.x());
    g.height[size_t(row)] = std::max(g.height[size_t(row)], size.y());
  };
  for (size_t k = 0; k < panels.size(); ++k) widen(panels[k].view.column, panels[k].view.row, real[k].drawing_mm * ratio);
  const SectionCell section = section_cell(panels, real[0], params, ratio);
  if (section.column >= 0) widen(section.column, section.row, section.size_mm);
  return g;
}

// The panel's raster copied into the page's at its place (whole pixels: the views line up within one).
void paste(cv::Mat& page, const cv::Mat& panel, const Vec2& at_mm, double px_per_mm) {
  const int x = int(std::lround(at_mm.x() * px_per_mm)), y = int(std::lround(at_mm.y() * px_per_mm));
  const cv::Rect into = cv::Rect(x, y, panel.cols, panel.rows) & cv::Rect(0, 0, page.cols, page.rows);
  if (into.area() > 0) panel(cv::Rect(0, 0, into.width, into.height)).copyTo(page(into));
}


// The frame of the default view: its direction along the least extent (or the relief's facing
// side), its up.
ObjectFrame viewed_frame(const TriMesh& mesh) {
  const PlateView v = default_view(mesh);
  ObjectFrame f;
  f.front = -v.direction.normalized();
  f.up = (v.up - v.up.dot(f.front) * f.front).normalized();
  f.how = "the front " + v.name;
  return f;
}

// The face turned to `side`: the faces turned less than 45 degrees from it (the face proper, not
// the walls round it), their area and how far they depart from a plane (the area-weighted standard
// deviation of their depth along `side`). A cuneiform tablet's reverse bulges, a tool's dorsal face
// is ridged; a scan of one side only has next to no area facing the other way.
struct Face {
  double area = 0, bulge = 0;
};
Face face_towards(const TriMesh& mesh, const Vec3& side) {
  double area = 0, sum = 0, sum2 = 0;
  for (const auto& t : mesh.faces) {
    const Vec3 &a = mesh.vertices[size_t(t[0])], &b = mesh.vertices[size_t(t[1])], &c = mesh.vertices[size_t(t[2])];
    const Vec3 n = (b - a).cross(c - a);
    const double w = 0.5 * n.norm();
    if (!(w > 0) || n.dot(side) < std::sqrt(0.5) * 2 * w) continue;
    const double depth = side.dot(a + b + c) / 3;
    area += w, sum += w * depth, sum2 += w * depth * depth;
  }
  if (!(area > 0)) return {};
  return {area, std::sqrt(std::max(0.0, sum2 / area - (sum / area) * (sum / area)))};
}

// The skewness of the surface's area along `axis`: positive when its long tail (a tool's tip) lies
// towards +axis and its bulk (the butt) towards -axis.
double area_skewness(const TriMesh& mesh, const Vec3& axis) {
  double total = 0, mean = 0;
  std::vector<std::pair<double, double>> along;
  for (const auto& t : mesh.faces) {
    const Vec3 &a = mesh.vertices[size_t(t[0])], &b = mesh.vertices[size_t(t[1])], &c = mesh.vertices[size_t(t[2])];
    const double area = 0.5 * (b - a).cross(c - a).norm(), x = axis.dot(a + b + c) / 3;
    along.emplace_back(x, area), total += area, mean += area * x;
  }
  if (!(total > 0)) return 0;
  mean /= total;
  double m2 = 0, m3 = 0;
  for (const auto& [x, area] : along) m2 += area * (x - mean) * (x - mean), m3 += area * std::pow(x - mean, 3);
  return m2 > 0 ? m3 / total / std::pow(m2 / total, 1.5) : 0;
}

constexpr double kSidesAlike = 0.1;     // bulges within this share of the larger: neither face is the flatter
constexpr double kEndsAlike = 0.1;      // a skewness under this: neither end is the butt
constexpr double kScanUpInFaceDeg = 70; // as kScanUpKeptDeg, within the face's plane

// The scan's up: its y, or its z when the front runs along y (a scan lying flat).
Vec3 scan_up(const Vec3& front) { return std::abs(front.y()) < 0.9 ? Vec3::UnitY() : Vec3::UnitZ(); }

// `axis` pointing the way `towards` does (kept when square to it).
Vec3 signed_like(const Vec3& axis, const Vec3& towards) { return axis.dot(towards) < 0 ? Vec3(-axis) : axis; }

std::string number(double x) {
  char text[32];
  std::snprintf(text, sizeof text, "%.3g", x);
  return text;
}

constexpr double kOneSided = 0.1;  // a back facing less than this share of the front's area: a one-sided scan

// A flat find's frame: the front along `normal`, its least extent (its flattest faces), on the
// flatter face when `front_flatter`, else on the less flat one; on the scanned face of a scan of one
// side. The log names the two faces and their bulges.
ObjectFrame two_sided_frame(const TriMesh& mesh, const Vec3& normal, bool front_flatter, const std::string& front_name,
                            const std::string& back_name) {
  ObjectFrame f = viewed_frame(mesh);
  const Face plus = face_towards(mesh, normal), minus = face_towards(mesh, -normal);
  if (std::min(plus.area, minus.area) < kOneSided * std::max(plus.area, minus.area)) {
    f.front = plus.area > minus.area ? normal : Vec3(-normal);
    f.how = "a scan of one side: the " + front_name + " the scanned face";
    return f;
  }
  if (std::abs(plus.bulge - minus.bulge) < kSidesAlike * std::max(plus.bulge, minus.bulge)) {
    f.how = "both faces alike: the " + front_name + " the side MeshLab shows first";
    return f;
  }
  const bool plus_flatter = plus.bulge < minus.bulge;
  const bool plus_front = plus_flatter == front_flatter;
  f.front = plus_front ? normal : Vec3(-normal);
  const Face& front = plus_front ? plus : minus;
  const Face& back = plus_front ? minus : plus;
  f.how = "the " + front_name + " the " + (front_flatter ? "flatter face" : "less flat") + " (its depth varies by " +
          number(front.bulge) + " units, the " + back_name + "'s by " + number(back.bulge) + ")";
  return f;
}

// The side of `axis` (+axis or -axis) with next to nothing facing it — a scan of one side's
// unscanned side — or zero when both sides have surface.
Vec3 unscanned_side(const TriMesh& mesh, const Vec3& axis) {
  const double plus = face_towards(mesh, axis).area, minus = face_towards(mesh, -axis).area;
  if (minus < kOneSided * plus) return -axis;
  if (plus < kOneSided * minus) return axis;
  return Vec3::Zero();
}

// A tablet: the front along its least extent (its flattest faces), the obverse the flatter of the
// two (a cuneiform tablet's reverse bulges), up the scan's up within the face unless the face's
// long axis lies more than kScanUpInFaceDeg from it (a tablet scanned on its side: then that axis).
ObjectFrame tablet_frame(const TriMesh& mesh) {
  const auto axes = surface_axes(mesh);
  const Vec3 longest = axes.eigenvectors().col(2);
  ObjectFrame f = two_sided_frame(mesh, axes.eigenvectors().col(0), true, "obverse", "reverse");
  Vec3 up = scan_up(f.front);
  up -= up.dot(f.front) * f.front;
  const Vec3 along = longest - longest.dot(f.front) * f.front;
  const double off = up.norm() > 1e-6 ? std::acos(std::min(1.0, std::abs(up.normalized().dot(along.normalized())))) * 180 / M_PI : 90;
  if (off <= kScanUpInFaceDeg) {
    f.up = up.normalized(), f.how += ", the scan's up kept";
  } else {
    f.up = signed_like(along.normalized(), up.norm() > 1e-6 ? up : scan_up(f.front)), f.how += ", its long axis up";
  }
  return f;
}

// A knapped tool: the front along its least extent, the dorsal face the less flat of the two (the
// ventral face is the flake's smooth inner side), its long axis up with the tip up and the butt
// (where the surface's bulk lies) down, as lithic drawings are oriented.
ObjectFrame lithic_frame(const TriMesh& mesh) {
  const auto axes = surface_axes(mesh);
  const Vec3 longest = axes.eigenvectors().col(2);
  ObjectFrame f = two_sided_frame(mesh, axes.eigenvectors().col(0), false, "dorsal face", "ventral face");
  const double skew = area_skewness(mesh, longest);
  if (std::abs(skew) >= kEndsAlike) {
    f.up = skew > 0 ? longest : Vec3(-longest), f.how += ", its long axis up, the butt (the bulk of its surface) down";
  } else {
    f.up = signed_like(longest, scan_up(f.front)), f.how += ", its long axis up (neither end the bulkier: the scan's up kept)";
  }
  f.up = (f.up - f.up.dot(f.front) * f.front).normalized();
  return f;
}

// The first view's section (the cut through its drawing placed at `drawing_at`, from the page's
// drawing origin) in its cell, aligned with the drawing, named below.
void add_layout_section(Plate& plate, const PlatePanel& first, const PageFrame& frame, const Grid& grid, const SectionCell& cell,
                        const Vec2& drawing_at, const PlateParams& params) {
  if (cell.column < 0) return;
  const Vec2 origin = grid.cell_origin(cell.column, cell.row);
  const Vec2 profile_at = params.section.axis == SectionAxis::horizontal ? Vec2(drawing_at.x(), origin.y()) : Vec2(origin.x(), drawing_at.y());
  SectionDrawing drawn = section_drawing(*first.mesh, frame, params, plate.drawing_origin_mm + drawing_at, plate.drawing_origin_mm + profile_at);
  for (PlatePath& path : drawn.paths) plate.paths.push_back(std::move(path));
  plate.section_segments = drawn.segments;
  const Vec2 below = plate.drawing_origin_mm + origin + Vec2(0.5 * grid.width[size_t(cell.column)], grid.height[size_t(cell.row)] + 4);
  plate.texts.push_back(PlateText{below, "section", kNameSize});
}

// The layout's views in their cells (the convention's names, directions and ups).
std::vector<LayoutView> layout_cells(PlateLayout layout, const ObjectFrame& f) {
  const Vec3 n = f.front, u = f.up, r = u.cross(n);  // r: to the page's right in the front view
  switch (layout) {
    case PlateLayout::one_view:
      return {view("front", -n, u, 0, 0)};
    case PlateLayout::tablet:
      return {view("obverse", -n, u, 1, 1),    view("top edge", -u, -n, 1, 0),   view("left edge", r, u, 0, 1),
              view("right edge", -r, u, 2, 1), view("bottom edge", u, n, 1, 2), view("reverse", n, -u, 1, 3)};
    case PlateLayout::lithic:
      return {view("dorsal face", -n, u, 0, 0), view("right profile", -r, u, 1, 0), view("ventral face", n, u, 2, 0)};
    case PlateLayout::two_faces:
      return {view("obverse", -n, u, 0, 0), view("reverse", n, u, 1, 0)};
    case PlateLayout::figurine:
      return {view("front", -n, u, 0, 0), view("right side", r, u, 1, 0), view("back", n, u, 2, 0)};
  }
  return {};
}

}  // namespace

ObjectFrame object_frame(const TriMesh& mesh, PlateLayout layout, bool turn_over, bool upside_down) {
  ObjectFrame f = layout == PlateLayout::tablet ? tablet_frame(mesh) : layout == PlateLayout::lithic ? lithic_frame(mesh) : viewed_frame(mesh);
  if (turn_over) f.front = -f.front, f.how += "; turned over";
  if (upside_down) f.up = -f.up, f.how += "; upside down";
  f.unscanned = unscanned_side(mesh, f.front);
  if (f.unscanned != Vec3::Zero() && layout != PlateLayout::one_view)
    f.warning = std::string("Warning: a scan of one side (next to nothing faces its ") + (f.unscanned.dot(f.front) > 0 ? "front" : "back") +
                "): the views of that side show the scan's underside, named \"(not scanned)\"" +
                (layout == PlateLayout::two_faces ? "; give the other side's scan as Reverse layer (Two faces)." : ".");
  return f;
}

// The layout's views, those of a scan's unscanned side named "(not scanned)".
std::vector<LayoutView> layout_views(PlateLayout layout, const ObjectFrame& f) {
  std::vector<LayoutView> views = layout_cells(layout, f);
  for (LayoutView& v : views)
    if (-v.view.direction.dot(f.unscanned) > 0.5) v.name += " (not scanned)", v.view.name = v.name;
  return views;
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
  plate.real_size_mm = real[0].drawing_mm;  // the main view's: the object's size, for the unit's check
  plate.ratio = params.ratio > 0 ? params.ratio : standard_ratio([&](double ratio) { return grid_of(panels, real, ratio, params).size(); }, params);
  const Grid grid = grid_of(panels, real, plate.ratio, params);
  PlateParams one = params;
  one.section.axis = SectionAxis::none;
  Plate page = make_plate_page(grid.size(), params);  // the page, its margins and the bar's room
  plate.width_mm = page.width_mm, plate.height_mm = page.height_mm, plate.drawing_origin_mm = page.drawing_origin_mm;
  plate.drawing_size_mm = grid.size();
  const double px_per_mm = params.dpi / 25.4;
  plate.shading = cv::Mat(int(std::ceil(grid.size().y() * px_per_mm)) + 1, int(std::ceil(grid.size().x() * px_per_mm)) + 1, CV_8U,
                          cv::Scalar(255));
  // Each view outlined with the heavy pen, as finds are drawn (the outline heavier than the lines within).
  double curve_width = 0;
  for (const PlatePanel& p : panels)
    for (const PlateCurves& l : p.layers ? *p.layers : std::vector<PlateCurves>{}) curve_width = std::max(curve_width, l.width_mm);
  if (!(curve_width > 0)) curve_width = PlateCurves().width_mm;
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
                                  frame, one, kOutlineWeight * curve_width);
    paste(plate.shading, drawn.shading, snapped, px_per_mm);
    for (PlatePath& path : drawn.paths) {
      for (Vec2& q : path.points) q += snapped + plate.drawing_origin_mm;
      plate.paths.push_back(std::move(path));
    }
    plate.visible_segments += drawn.visible, plate.hidden_segments += drawn.hidden, plate.outside_segments += drawn.outside;
    const Vec2 below = plate.drawing_origin_mm + cell + Vec2(0.5 * grid.width[size_t(p.view.column)], grid.height[size_t(p.view.row)] + 4);
    plate.texts.push_back(PlateText{below, p.view.name, kNameSize});
    if (k == 0) add_layout_section(plate, p, frame, grid, section_cell(panels, real[0], params, plate.ratio), snapped, params);
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
