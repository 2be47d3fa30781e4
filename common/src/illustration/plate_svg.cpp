// ReliefKit — the plate as SVG, written from its page description (page_marks): millimetre units,
// the shading as an embedded PNG, one group per curve layer, the texts, the scale bar. See plate.h.
#include <opencv2/imgcodecs.hpp>
#include <cstdio>
#include <sstream>

#include "reliefkit/illustration/plate.h"

namespace reliefkit {
namespace {

std::string base64(const std::vector<uchar>& bytes) {
  static const char* table = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  out.reserve((bytes.size() + 2) / 3 * 4);
  for (size_t i = 0; i < bytes.size(); i += 3) {
    const unsigned v = unsigned(bytes[i]) << 16 | (i + 1 < bytes.size() ? unsigned(bytes[i + 1]) << 8 : 0u) |
                       (i + 2 < bytes.size() ? unsigned(bytes[i + 2]) : 0u);
    out += table[(v >> 18) & 63];
    out += table[(v >> 12) & 63];
    out += i + 1 < bytes.size() ? table[(v >> 6) & 63] : '=';
    out += i + 2 < bytes.size() ? table[v & 63] : '=';
  }
  return out;
}

std::string escaped(const std::string& s) {
  std::string out;
  for (char c : s) out += c == '<' ? "&lt;" : c == '>' ? "&gt;" : c == '&' ? "&amp;" : c == '"' ? "&quot;" : std::string(1, c);
  return out;
}

void write_shading(std::ostringstream& svg, const Plate& p, const PageMark& m) {
  std::vector<uchar> png;
  if (p.shading.empty() || !cv::imencode(".png", p.shading, png)) return;
  const Vec2 size = m.points[1] - m.points[0];
  svg << " <image x=\"" << m.points[0].x() << "\" y=\"" << m.points[0].y() << "\" width=\"" << size.x() << "\" height=\"" << size.y()
      << "\" preserveAspectRatio=\"none\" href=\"data:image/png;base64," << base64(png) << "\"/>\n";
}

void write_path(std::ostringstream& svg, const PageMark& m) {
  svg << "  <path stroke-width=\"" << m.width_mm;
  if (!m.dashes.empty()) {
    svg << "\" stroke-dasharray=\"";
    char dash[32];
    for (size_t k = 0; k < m.dashes.size(); ++k) std::snprintf(dash, sizeof dash, "%s%g", k ? " " : "", m.dashes[k]), svg << dash;
  }
  if (!m.round_caps) svg << "\" stroke-linecap=\"butt";
  svg << (m.filled ? "\" fill=\"black" : "") << "\" d=\"M";
  for (size_t k = 0; k < m.points.size(); ++k) svg << (k ? " " : "") << m.points[k].x() << ',' << m.points[k].y();
  svg << (m.filled ? " Z" : "") << "\"/>\n";
}

void write_text(std::ostringstream& svg, const PageMark& m) {
  svg << "  <text x=\"" << m.points[0].x() << "\" y=\"" << m.points[0].y() << "\" font-size=\"" << m.size_mm << "\""
      << (m.centred ? " text-anchor=\"middle\"" : "") << ">" << escaped(m.text) << "</text>\n";
}

// A group per run of marks of one group: the curve layers, the texts, the scale bar.
void open_group(std::ostringstream& svg, const PageMark& m) {
  if (m.kind == PageMark::Kind::text)
    svg << " <g id=\"" << escaped(m.group) << "\" font-family=\"DejaVu Sans, sans-serif\" fill=\"black\">\n";
  else
    svg << " <g id=\"" << escaped(m.group) << "\" fill=\"none\" stroke=\"black\" stroke-linecap=\"round\" stroke-linejoin=\"round\">\n";
}
}  // namespace

std::string plate_svg(const Plate& p) {
  std::ostringstream svg;
  svg.precision(6);
  svg << std::fixed;
  svg << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
      << "<svg xmlns=\"http://www.w3.org/2000/svg\" version=\"1.1\" width=\"" << p.width_mm << "mm\" height=\"" << p.height_mm
      << "mm\" viewBox=\"0 0 " << p.width_mm << ' ' << p.height_mm << "\">\n"
      << " <rect x=\"0\" y=\"0\" width=\"" << p.width_mm << "\" height=\"" << p.height_mm << "\" fill=\"white\"/>\n";
  std::string group;
  bool open = false;
  for (const PageMark& m : page_marks(p)) {
    if (m.kind == PageMark::Kind::shading) {
      write_shading(svg, p, m);
      continue;
    }
    if (!open || m.group != group) {
      if (open) svg << " </g>\n";
      open_group(svg, m);
      group = m.group, open = true;
    }
    if (m.kind == PageMark::Kind::path) write_path(svg, m);
    else write_text(svg, m);
  }
  if (open) svg << " </g>\n";
  svg << "</svg>\n";
  return svg.str();
}

}  // namespace reliefkit
