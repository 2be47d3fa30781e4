// ReliefKit — the plate as SVG: millimetre units, the shading as an embedded PNG, one group of
// paths per curve layer, the scale bar. See plate.h.
#include <opencv2/imgcodecs.hpp>
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

void write_shading(std::ostringstream& svg, const Plate& p) {
  std::vector<uchar> png;
  if (p.shading.empty() || !cv::imencode(".png", p.shading, png)) return;
  svg << " <image x=\"" << p.drawing_origin_mm.x() << "\" y=\"" << p.drawing_origin_mm.y() << "\" width=\""
      << p.drawing_size_mm.x() << "\" height=\"" << p.drawing_size_mm.y()
      << "\" preserveAspectRatio=\"none\" href=\"data:image/png;base64," << base64(png) << "\"/>\n";
}

void write_paths(std::ostringstream& svg, const Plate& p) {
  std::string layer = "\x01";
  for (const auto& path : p.paths) {
    if (path.layer != layer) {
      if (layer != "\x01") svg << " </g>\n";
      layer = path.layer;
      svg << " <g id=\"" << escaped(layer) << "\" fill=\"none\" stroke=\"black\" stroke-linecap=\"round\" stroke-linejoin=\"round\">\n";
    }
    svg << "  <path stroke-width=\"" << path.width_mm << (path.dash_dot ? "\" stroke-dasharray=\"3 1 0.5 1" : "")
        << (path.filled ? "\" fill=\"black" : "") << "\" d=\"M";
    for (size_t k = 0; k < path.points.size(); ++k) svg << (k ? " " : "") << path.points[k].x() << ',' << path.points[k].y();
    svg << (path.filled ? " Z" : "") << "\"/>\n";
  }
  if (layer != "\x01") svg << " </g>\n";
}

void write_scale_bar(std::ostringstream& svg, const Plate& p) {
  const double x = p.bar_start_mm.x(), y = p.bar_start_mm.y(), len = p.bar_length_mm;
  svg << " <g id=\"scale bar\" stroke=\"black\" stroke-width=\"0.3\">\n"
      << "  <line x1=\"" << x << "\" y1=\"" << y << "\" x2=\"" << x + len << "\" y2=\"" << y << "\"/>\n"
      << "  <line x1=\"" << x << "\" y1=\"" << y - 1 << "\" x2=\"" << x << "\" y2=\"" << y + 1 << "\"/>\n"
      << "  <line x1=\"" << x + len << "\" y1=\"" << y - 1 << "\" x2=\"" << x + len << "\" y2=\"" << y + 1 << "\"/>\n"
      << " </g>\n"
      << " <text x=\"" << x + 0.5 * len << "\" y=\"" << y + 4 << "\" font-family=\"DejaVu Sans, sans-serif\" font-size=\"3\" "
      << "text-anchor=\"middle\">" << escaped(p.bar_label) << "</text>\n"
      << " <text x=\"" << x + len + 4 << "\" y=\"" << y + 1.1
      << "\" font-family=\"DejaVu Sans, sans-serif\" font-size=\"3\">" << escaped(p.scale_label) << "</text>\n";
}
void write_texts(std::ostringstream& svg, const Plate& p) {
  for (const PlateText& t : p.texts)
    svg << " <text x=\"" << t.at.x() << "\" y=\"" << t.at.y() << "\" font-family=\"DejaVu Sans, sans-serif\" font-size=\""
        << t.size_mm << "\" text-anchor=\"middle\">" << escaped(t.text) << "</text>\n";
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
  write_shading(svg, p);
  write_paths(svg, p);
  write_texts(svg, p);
  write_scale_bar(svg, p);
  svg << "</svg>\n";
  return svg.str();
}

}  // namespace reliefkit
