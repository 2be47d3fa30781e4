// ReliefKit — the plate's page description: everything drawn, in millimetres, once for the SVG and
// the PDF writers. See plate.h.
#include <cstdio>

#include "reliefkit/illustration/plate.h"

namespace reliefkit {
namespace {

PageMark path_mark(const std::string& group, std::vector<Vec2> points, double width_mm) {
  PageMark m;
  m.kind = PageMark::Kind::path, m.group = group, m.points = std::move(points), m.width_mm = width_mm;
  return m;
}

PageMark text_mark(const Vec2& at, const std::string& text, double size_mm, bool centred) {
  PageMark m;
  m.kind = PageMark::Kind::text, m.group = "texts", m.points = {at}, m.text = text, m.size_mm = size_mm, m.centred = centred;
  return m;
}

// A line of bar_length_mm with a tick at each end, its real length below, the scale beside it.
void add_scale_bar(const Plate& p, std::vector<PageMark>& marks) {
  const double x = p.bar_start_mm.x(), y = p.bar_start_mm.y(), len = p.bar_length_mm;
  for (const auto& line : {std::vector<Vec2>{Vec2(x, y), Vec2(x + len, y)}, std::vector<Vec2>{Vec2(x, y - 1), Vec2(x, y + 1)},
                           std::vector<Vec2>{Vec2(x + len, y - 1), Vec2(x + len, y + 1)}}) {
    PageMark m = path_mark("scale bar", line, 0.3);
    m.round_caps = false;
    marks.push_back(m);
  }
  marks.push_back(text_mark(Vec2(x + 0.5 * len, y + 4), p.bar_label, 3, true));
  marks.push_back(text_mark(Vec2(x + len + 4, y + 1.1), p.scale_label, 3, false));
}

}  // namespace

const std::vector<double>& dash_dot_mm() {
  static const std::vector<double> pattern{3, 1, 0.5, 1};
  return pattern;
}

std::vector<PageMark> page_marks(const Plate& p) {
  std::vector<PageMark> marks;
  if (!p.shading.empty()) {
    PageMark m;
    m.kind = PageMark::Kind::shading, m.group = "shading";
    m.points = {p.drawing_origin_mm, p.drawing_origin_mm + p.drawing_size_mm};
    marks.push_back(m);
  }
  for (const PlatePath& path : p.paths) {
    PageMark m = path_mark(path.layer, path.points, path.width_mm);
    if (path.dash_dot) m.dashes = dash_dot_mm(), m.round_caps = false;
    m.filled = path.filled;
    marks.push_back(std::move(m));
  }
  for (const PlateText& t : p.texts) marks.push_back(text_mark(t.at, t.text, t.size_mm, true));
  add_scale_bar(p, marks);
  return marks;
}

std::vector<std::string> plate_warnings(const Plate& plate, double unit_mm) {
  const double size = std::max(plate.real_size_mm.x(), plate.real_size_mm.y());
  if (size <= 1000 && size >= 5) return {};
  char text[400];
  std::snprintf(text, sizeof text,
                "Warning: the object %.4g x %.4g mm at %g mm per unit: if that is not its size, the scan is not in that "
                "unit — set Mesh unit (mm) to the scan's unit (the plate's scale and scale bar assume it).",
                plate.real_size_mm.x(), plate.real_size_mm.y(), unit_mm);
  return {text};
}

}  // namespace reliefkit
