// ReliefKit — the illustrator's plate of a scan: an orthographic view at a stated scale, the
// curve layers as black vector lines (hidden parts removed by depth), the surface's shading as a
// grey raster under them, a scale bar. The page is laid out here in millimetres; plate_svg()
// writes it as SVG (the plugin adapter also draws it to PDF with Qt).
#pragma once

#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "reliefkit/base/mesh.h"

namespace reliefkit {

/// Looking along `direction` with `up` up the page (both in the mesh's frame; up is made
/// perpendicular to the direction).
struct PlateView {
  Vec3 direction{0, 0, -1};
  Vec3 up{0, 1, 0};
};

/// The view facing a relief: along its axis of least extent (the normal of a coin, a plaque, a
/// sherd), looking at the side its faces face most (their area-weighted normals); up along the scan's y axis (its z
/// axis when the view runs along y), as MeshLab shows the scan by default.
PlateView facing_view(const TriMesh& mesh);

/// Curves to draw: points and segments (pairs of point indices), the layer's stroke width and,
/// optionally, each point's strength (the curve filters' vertex quality) for the line weights.
struct PlateCurves {
  std::string name;
  std::vector<Vec3> points;
  std::vector<std::array<int, 2>> segments;
  double width_mm = 0.35;
  std::vector<double> strength;  // per point, or empty
};

/// How the lines' widths vary: the illustrator's two or three pen weights.
enum class LineWeights {
  by_strength,  // per curve: the strongest third of the curves' length 0.5/0.35 of the width, the weakest 0.25/0.35
  by_layer,     // the first layer 0.5/0.35 of the width, the second the width, the others 0.25/0.35
  one           // every line the width
};

/// A cross-section: the mesh cut by the plane through a vertical (or horizontal) line of the
/// drawing, its profile drawn beside the drawing (to the right; below for a horizontal one) at
/// the same scale, and the line marked dash-dot on the drawing.
enum class SectionAxis { none, vertical, horizontal };
struct PlateSection {
  SectionAxis axis = SectionAxis::none;
  double at = 0.5;  // the line's place: a fraction of the drawing's width (height), from its left (top)
  double width_mm = 0.5;  // of the profile
  bool fill = true;       // closed profiles (a closed mesh cut through) filled black
};

struct PlateParams {
  double unit_mm = 1;         // one unit of the mesh in millimetres (its scanner's unit)
  double ratio = 0;           // drawn size / real size: 1 for 1:1, 2 for 2:1, 0.5 for 1:2; 0: automatic
                              // (the largest standard scale at which the plate fits the page, A4 when fitted)
  double dpi = 300;           // the shading raster's resolution on the page
  double margin_mm = 10;      // around the drawing; the scale bar sits in the bottom margin
  double page_width_mm = 0;   // 0: the drawing and its margins; else a fixed page (A4: 210 x 297)
  double page_height_mm = 0;
  double hidden_px = 1.5;     // a curve point more than this behind the surface (in raster pixels) is hidden
  double simplify_px = 0.25;  // polylines simplified within this many raster pixels
  LineWeights weights = LineWeights::by_strength;
  PlateSection section;
  bool curves_required = true;  // false: a plate of the shading alone is allowed (a plain sherd's pottery plate)
  std::vector<std::vector<Vec3>> guides;  // lines drawn dash-dot over the drawing, never hidden (a rollout's seam)
  std::vector<std::string> titles;        // lines of text above the drawing (what the sheet is)
  Progress progress = nullptr;
};

/// A visible piece of curve on the page (millimetres, y down as in SVG and PDF).
struct PlatePath {
  std::vector<Vec2> points;
  double width_mm = 0.35;
  std::string layer;
  bool dash_dot = false;  // the section's line on the drawing
  bool filled = false;    // a closed profile of the section, filled black (the pottery convention)
};

/// A line of text on the page (millimetres, y down; the baseline's middle).
struct PlateText {
  Vec2 at{0, 0};
  std::string text;
  double size_mm = 3;
};

struct Plate {
  double width_mm = 0, height_mm = 0;
  std::vector<PlateText> texts;  // the pottery plate's rim diameter and share
  Vec2 drawing_origin_mm{0, 0};  // top-left of the drawing (and of the shading raster)
  Vec2 drawing_size_mm{0, 0};
  cv::Mat shading;               // 8-bit grey at params.dpi, 255 where there is no surface (paper)
  std::vector<PlatePath> paths;
  Vec2 bar_start_mm{0, 0};       // the scale bar: a line of bar_length_mm with its label below
  double bar_length_mm = 0;
  std::string bar_label;         // "10 mm"
  std::string scale_label;       // "1:1"
  double ratio = 1;              // the scale drawn (params.ratio, or the one chosen)
  Vec2 real_size_mm{0, 0};       // the object's extent in the view at params.unit_mm: a check of the unit
  long section_segments = 0;     // of the profile (section paths are in `paths`, layer "section")
  long visible_segments = 0, hidden_segments = 0;
  long outside_segments = 0;     // off the mesh's drawing (another mesh's curves): not drawn
};

/// The plate of `mesh` shaded with `grey` (per vertex, 0 black .. 1 white; empty: Lambertian from
/// the view) and the curve layers. Throws InputError for a view with no area, no curve to draw, a
/// page too small for the drawing at this scale, a section line that misses the mesh, curves
/// that are all hidden or all off the mesh's drawing, or parameters out of range.
Plate make_plate(const TriMesh& mesh, const std::vector<double>& grey, const std::vector<PlateCurves>& layers,
                 const PlateView& view, const PlateParams& params);

/// The pottery convention (issue 42) for a piece oriented by "Vessel Axis and Profile" (axis +Z
/// through the origin, the piece's middle towards +x, rim up): the axis a vertical dash-dot line;
/// left of it the section (its closed loops mirrored, filled black); right of it the exterior
/// seen from the front — the right half of a vessel kept whole enough (half of the rim or more),
/// a sherd whole beside the axis — with the curve layers on it; the rim line across both; the rim
/// diameter and the preserved share written above it. The scale as make_plate chooses it (the
/// standard scales 1:1, 1:2, 1:3, 1:4 ... at which the whole fits A4), counting the section's width.
struct PotterySheet {
  std::vector<std::vector<Vec2>> section;  // (radius, height) closed loops: the wall's section
  std::vector<std::vector<Vec2>> lines;    // (radius, height) open parts of the profile (no loop)
  bool has_rim = false;
  double rim_height = 0, rim_radius = 0;   // mesh units
  double rim_share = 0;                    // 0..1
};
Plate make_pottery_plate(const TriMesh& oriented, const std::vector<double>& grey, const std::vector<PlateCurves>& layers,
                         const PotterySheet& sheet, const PlateParams& params);

/// The plate as an SVG document (millimetre units; the shading embedded as a PNG).
std::string plate_svg(const Plate& plate);

}  // namespace reliefkit
