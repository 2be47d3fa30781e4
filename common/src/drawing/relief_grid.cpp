// The grid "Relief from Line Drawing" builds a relief on (plane or cylinder): its extent, spacing,
// step height and the pixel of each vertex. See drawing_relief.h.
#include <cmath>

#include "reliefkit/base/scale.h"
#include "reliefkit/drawing/drawing_relief.h"

namespace reliefkit {

cv::Rect relief_area(const DrawingCurves& curves, double margin) { return drawing_extent(curves, 4 * margin + 4); }

double relief_step_height(double percent, const cv::Rect& area, double pixel_size) {
  return percent / 100 * area.width * pixel_size;
}

ReliefGrid relief_grid(const DrawingCurves& curves, const DrawingInterpretation& di, const ReliefGridParams& p) {
  require_range(p.pixel_size, "Pixel size", 1e-12, 1e12);
  ReliefGrid g;
  g.area = relief_area(curves, p.margin);
  g.wanted_cell = p.cell > 0 ? p.cell : drawing_cell(di, p.margin);
  g.wanted_vertices = (g.area.width / g.wanted_cell + 1) * (g.area.height / g.wanted_cell + 1);
  g.cell = g.wanted_cell;
  if (p.cell <= 0 && g.wanted_vertices > double(p.max_vertices))
    g.cell = std::sqrt(double(g.area.width) * g.area.height / double(p.max_vertices));
  g.grid = drawing_grid(g.area.width, g.area.height, g.cell, p.pixel_size, g.area.x, g.area.y);
  g.pixel.reserve(g.grid.vertices.size());
  for (const Vec3& v : g.grid.vertices) g.pixel.emplace_back(v.x() / p.pixel_size, -v.y() / p.pixel_size);
  return g;
}

}  // namespace reliefkit
