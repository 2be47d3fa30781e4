// ReliefKit — the plate's cross-section: the mesh cut by a plane through a line of the drawing,
// its profile drawn beside the drawing at the same scale. See plate_raster.h.
#include <algorithm>
#include <cmath>

#include "plate_raster.h"
#include "reliefkit/base/zero_crossings.h"

namespace reliefkit {
namespace {

constexpr double kGapMm = 8;  // between the drawing and its profile

bool vertical(const PlateParams& p) { return p.section.axis == SectionAxis::vertical; }

// A point of the cut on the page: depth across (front at the left) beside a vertical section's
// drawing, depth down (front at the top) below a horizontal one's.
Vec2 profile_point(const Vec3& p, const PageFrame& f, const PlateParams& params, const Vec2& origin) {
  const Vec2 on_drawing = f.to_mm(p);
  const double depth_mm = (f.depth(p) - f.nearest) * f.mm_per_unit;
  return origin + (vertical(params) ? Vec2(depth_mm, on_drawing.y()) : Vec2(on_drawing.x(), depth_mm));
}

// The section's line across a drawing (top-left `o`, `size` in mm), 2 mm beyond it at both ends.
PlatePath section_line(const Vec2& o, const Vec2& size, const PlateParams& params) {
  PlatePath line{{}, 0.2, "section line", true};
  if (vertical(params)) {
    const double x = o.x() + params.section.at * size.x();
    line.points = {Vec2(x, o.y() - 2), Vec2(x, o.y() + size.y() + 2)};
  } else {
    const double y = o.y() + params.section.at * size.y();
    line.points = {Vec2(o.x() - 2, y), Vec2(o.x() + size.x() + 2, y)};
  }
  return line;
}
}  // namespace

Vec2 section_room_mm(const PageFrame& frame, const PlateParams& params) {
  if (params.section.axis == SectionAxis::none) return Vec2::Zero();
  const double depth_mm = (frame.farthest - frame.nearest) * frame.mm_per_unit + kGapMm;
  return vertical(params) ? Vec2(depth_mm, 0) : Vec2(0, depth_mm);
}

SectionDrawing section_drawing(const TriMesh& mesh, const PageFrame& frame, const PlateParams& params, const Vec2& drawing_at,
                               const Vec2& profile_at) {
  SectionDrawing drawn;
  if (params.section.axis == SectionAxis::none) return drawn;
  const double at = params.section.at, per_mm = 1 / frame.mm_per_unit;
  const Vec3 normal = vertical(params) ? frame.right : frame.up;
  const double offset = vertical(params) ? frame.left + at * frame.drawing_mm.x() * per_mm : frame.top - at * frame.drawing_mm.y() * per_mm;
  const Polylines profile = plane_cut(mesh, normal, offset);
  if (profile.segments.empty())
    throw InputError("The section's line misses the mesh: place it across the object (0.5 is through the middle).");
  for (const auto& chain : profile.chains()) {
    PlatePath path{{}, params.section.width_mm, "section", false, params.section.fill && chain.size() > 3 && chain.front() == chain.back()};
    for (int k : chain) path.points.push_back(profile_point(profile.points[size_t(k)], frame, params, profile_at));
    drawn.paths.push_back(std::move(path));
  }
  drawn.segments = long(profile.segments.size());
  drawn.paths.push_back(section_line(drawing_at, frame.drawing_mm, params));
  return drawn;
}

void add_section(Plate& plate, const TriMesh& mesh, const PageFrame& frame, const PlateParams& params) {
  const Vec2 o = plate.drawing_origin_mm, beside = vertical(params) ? Vec2(frame.drawing_mm.x() + kGapMm, 0) : Vec2(0, frame.drawing_mm.y() + kGapMm);
  SectionDrawing drawn = section_drawing(mesh, frame, params, o, o + beside);
  for (PlatePath& path : drawn.paths) plate.paths.push_back(std::move(path));
  plate.section_segments = drawn.segments;
}

}  // namespace reliefkit
