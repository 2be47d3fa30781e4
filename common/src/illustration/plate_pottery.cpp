// ReliefKit — the pottery plate: a piece on its axis in the half-section convention. See plate.h.
#include <algorithm>
#include <cmath>
#include <cstdio>

#include "plate_raster.h"

namespace reliefkit {
namespace {


// What the exterior view shows: for a piece with half its rim or more (a vessel), its right half
// (y >= 0); for a sherd, the whole of it moved beside the axis (its least y to 0).
struct Exterior {
  TriMesh mesh;
  std::vector<double> grey;
  std::vector<PlateCurves> layers;
};
Exterior exterior_of(const TriMesh& oriented, const std::vector<double>& grey, const std::vector<PlateCurves>& layers,
                     bool vessel) {
  Exterior e{oriented, grey, layers};
  if (vessel) {  // the faces at y >= 0 and their vertices (renumbered; the grey with them)
    std::vector<int> index(oriented.vertices.size(), -1);
    e.mesh.vertices.clear(), e.mesh.faces.clear(), e.grey.clear();
    for (const auto& f : oriented.faces) {
      if (oriented.vertices[size_t(f[0])].y() + oriented.vertices[size_t(f[1])].y() + oriented.vertices[size_t(f[2])].y() < 0)
        continue;
      std::array<int, 3> g{};
      for (int k = 0; k < 3; ++k) {
        int& i = index[size_t(f[size_t(k)])];
        if (i < 0) {
          i = e.mesh.n_vertices();
          e.mesh.vertices.push_back(oriented.vertices[size_t(f[size_t(k)])]);
          if (!grey.empty()) e.grey.push_back(grey[size_t(f[size_t(k)])]);
        }
        g[size_t(k)] = i;
      }
      e.mesh.faces.push_back(g);
    }
    for (PlateCurves& l : e.layers) {
      std::vector<std::array<int, 2>> segments;
      for (const auto& s : l.segments)
        if (l.points[size_t(s[0])].y() >= 0 && l.points[size_t(s[1])].y() >= 0) segments.push_back(s);
      l.segments = segments;
    }
    return e;
  }
  double least = INFINITY;
  for (const Vec3& p : oriented.vertices) least = std::min(least, p.y());
  for (Vec3& p : e.mesh.vertices) p.y() -= least;
  for (PlateCurves& l : e.layers)
    for (Vec3& p : l.points) p.y() -= least;
  return e;
}

double widest(const PotterySheet& s) {
  double r = 0;
  for (const auto& set : {&s.section, &s.lines})
    for (const auto& loop : *set)
      for (const Vec2& q : loop) r = std::max(r, q.x());
  return r;
}

// Everything on the plate moved right by dx (room for the section left of the axis).
void shift_right(Plate& plate, double dx) {
  plate.width_mm += dx;
  plate.drawing_origin_mm.x() += dx;
  plate.bar_start_mm.x() += dx;
  for (PlatePath& path : plate.paths)
    for (Vec2& q : path.points) q.x() += dx;
}

// The section (mirrored left of the axis, filled), the axis, the rim line and its figures.
void add_pottery_marks(Plate& plate, const PotterySheet& sheet, const PageFrame& frame, double axis_x, double width_mm) {
  auto page = [&](const Vec2& rz) {
    return Vec2(axis_x - rz.x() * frame.mm_per_unit, plate.drawing_origin_mm.y() + (frame.top - rz.y()) * frame.mm_per_unit);
  };
  for (const auto& loop : sheet.section) {
    PlatePath path{{}, width_mm, "section", false, true};
    for (const Vec2& q : loop) path.points.push_back(page(q));
    plate.paths.push_back(std::move(path));
  }
  for (const auto& line : sheet.lines) {
    PlatePath path{{}, width_mm, "section", false, false};
    for (const Vec2& q : line) path.points.push_back(page(q));
    plate.paths.push_back(std::move(path));
  }
  const double top = plate.drawing_origin_mm.y(), bottom = top + plate.drawing_size_mm.y();
  plate.paths.push_back(PlatePath{{Vec2(axis_x, top - 3), Vec2(axis_x, bottom + 3)}, 0.2, "axis", true, false});
  if (!sheet.has_rim) return;
  // The rim line: from the section's rim to the axis, and on across the exterior of a vessel.
  const double y = page(Vec2(0, sheet.rim_height)).y(), half = sheet.rim_radius * frame.mm_per_unit;
  const double right = sheet.rim_share >= 0.5 ? axis_x + half : axis_x;
  plate.paths.push_back(PlatePath{{Vec2(axis_x - half, y), Vec2(right, y)}, 0.25, "rim line", false, false});
  char text[80];
  std::snprintf(text, sizeof text, "\xC3\x98 %.0f mm, %.0f %%", 2 * sheet.rim_radius * frame.mm_per_unit / plate.ratio,
                100 * sheet.rim_share);
  plate.texts.push_back(PlateText{Vec2(axis_x, y - 2), text, 3});
}

}  // namespace

// The exterior as seen from +x (the piece's middle), up the axis; page right is +y.
PlateView pottery_front_view() {
  PlateView v;
  v.direction = Vec3(-1, 0, 0);
  v.up = Vec3(0, 0, 1);
  v.name = "the pottery convention's exterior, from the piece's middle";
  return v;
}

Plate make_pottery_plate(const TriMesh& oriented, const std::vector<double>& grey, const std::vector<PlateCurves>& layers,
                         const PotterySheet& sheet, const PlateParams& params) {
  if (sheet.section.empty() && sheet.lines.empty())
    throw InputError("The piece has no profile to draw: run \"Vessel Axis and Profile\" on it first.");
  const Exterior e = exterior_of(oriented, grey, layers, sheet.rim_share >= 0.5);
  const PlateView view = pottery_front_view();
  const PageFrame real = page_frame(e.mesh, view, params.unit_mm);
  const double section_real_mm = widest(sheet) * params.unit_mm;
  PlateParams p = params;
  p.section.axis = SectionAxis::none;
  p.curves_required = false;
  if (p.ratio <= 0)
    p.ratio = standard_ratio(
        [&](double ratio) -> Vec2 {  // pottery is drawn at 1:1 or reduced, never enlarged
          return ratio > 1 ? Vec2(1e12, 1e12) : Vec2(Vec2(real.drawing_mm.x() + section_real_mm, real.drawing_mm.y()) * ratio);
        },
        p);
  Plate plate = make_plate(e.mesh, e.grey, e.layers, view, p);
  const PageFrame frame = page_frame(e.mesh, view, params.unit_mm * plate.ratio);
  const double section_mm = section_real_mm * plate.ratio;
  if (params.page_width_mm > 0) {  // a fixed page: the content re-centred, the page kept
    shift_right(plate, section_mm / 2);
    plate.width_mm -= section_mm / 2;
    if (plate.drawing_origin_mm.x() - section_mm < 0.5 * params.margin_mm)
      throw InputError("At this scale the section and the exterior do not fit the page side by side: choose a smaller "
                       "scale or a larger page.");
  } else {
    shift_right(plate, section_mm);
  }
  const double axis_x = plate.drawing_origin_mm.x() - frame.left * frame.mm_per_unit;  // where y = 0 falls
  add_pottery_marks(plate, sheet, frame, axis_x, params.section.width_mm);
  return plate;
}

}  // namespace reliefkit
