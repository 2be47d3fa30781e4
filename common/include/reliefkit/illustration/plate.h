// ReliefKit — the illustrator's plate of a scan: an orthographic view at a stated scale, the
// curve layers as black vector lines (hidden parts removed by depth), the surface's shading as a
// grey raster under them, a scale bar. The page is laid out here in millimetres; plate_svg()
// writes it as SVG (the plugin adapter also draws it to PDF with Qt).
#pragma once

#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "reliefkit/base/mesh.h"
#include "reliefkit/base/surface.h"

namespace reliefkit {

/// Looking along `direction` with `up` up the page (both in the mesh's frame; up is made
/// perpendicular to the direction).
struct PlateView {
  Vec3 direction{0, 0, -1};
  Vec3 up{0, 1, 0};
  std::string name;  // how it was chosen, for the log ("facing the relief", "upright, facing its widest side")
};

/// The view facing a relief: along its axis of least extent (the normal of a coin, a plaque, a
/// sherd), looking at the side its faces face most (their area-weighted normals); up along the scan's y axis (its z
/// axis when the view runs along y), as MeshLab shows the scan by default.
PlateView facing_view(const TriMesh& mesh);

/// The default view (issue 44): a relief — its least extent under 0.35 of its middle one (a coin,
/// a plaque, a sherd) — faced (facing_view); any other object drawn upright as an illustrator
/// draws a figurine or a bust: the scan's y up (as MeshLab shows it) unless its largest extent lies
/// more than 70 degrees from it (a scan lying on its side: then that extent up), looking along its
/// least extent at its widest side, from the side
/// MeshLab shows first (from +z; +x, +y when the view runs square to z). Extents are the surface's
/// (area-weighted), so that a decimated scan's dense patches do not pull them. `name` says which.
PlateView default_view(const TriMesh& mesh);

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
  Vec2 real_size_mm{0, 0};       // the object's extent in the (a layout's main) view at params.unit_mm: a check of the unit
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
/// The pottery plate's view of the exterior: from +x (the piece's middle), the axis up.
PlateView pottery_front_view();
Plate make_pottery_plate(const TriMesh& oriented, const std::vector<double>& grey, const std::vector<PlateCurves>& layers,
                         const PotterySheet& sheet, const PlateParams& params);

/// Shadings the core renders headless (issue 44): grey per vertex for the plate's raster.
enum class PlateShadingKind {
  raking,             // one light low over the surface from the azimuth and elevation given (a face square
                      // to the view: 0.65)
  multi_directional,  // lights from `directions` azimuths at 45 degrees, averaged: a slope shading
                      // (a face square to the view: 0.9; darker the more it is tilted, whichever way)
  openness,           // the sky-view factor: the share of the sky above each point not hidden by the surface
                      // within `radius_edges` edge lengths (ambient occlusion; LiDAR's openness)
  radiance_scaling    // light from the top left, brightened where the surface is convex and darkened where
                      // it is concave by its mean curvature (after Vergne et al. 2010)
};
struct PlateShadingParams {
  PlateShadingKind kind = PlateShadingKind::raking;
  double azimuth_deg = 315;   // where the light comes from: degrees clockwise from the top of the page (315: top left)
  double elevation_deg = 20;  // raking light's, above the surface's plane seen from the view (90: from the viewer)
  int directions = 8;         // multi-directional
  double radius_edges = 10;   // openness: how far the horizon is sought, in edge lengths
  double strength = 1;        // radiance scaling: how much the curvature brightens and darkens
  void validate() const;      // throws InputError naming the parameter
};

/// The direction towards a light at (azimuth, elevation) of the view, in the mesh's frame.
Vec3 light_direction(const PlateView& view, double azimuth_deg, double elevation_deg);

/// Grey per vertex (0 black .. 1 white) of `surface` seen from `view`.
std::vector<double> plate_shading(const Surface& surface, const PlateView& view, const PlateShadingParams& params);

/// A light stack for reflectance-transformation-imaging viewers (RTI, Relight): `count` images of
/// the surface at the plate's frame, each lit by raking light from one of `count` azimuths evenly
/// round (the first from the top of the page, clockwise) at `elevation_deg`; with the lights'
/// directions in the image's frame (x right, y up, z towards the viewer; unit).
struct LightStack {
  std::vector<cv::Mat> images;  // 8-bit grey, 255 off the surface
  std::vector<Vec3> directions;
};
LightStack light_stack(const Surface& surface, const PlateView& view, const PlateParams& params, double ratio, int count,
                       double elevation_deg);

/// The .lp file RTI viewers read: the number of images, then per image its file name and its
/// light's direction.
std::string lp_file(const std::vector<std::string>& image_names, const std::vector<Vec3>& directions);

/// The multi-view layouts finds are published in (issue 44), all views at one scale.
enum class PlateLayout {
  one_view,
  tablet,     // the "fat cross": obverse in the middle, the top edge above it, the bottom edge below,
              // the left and right edges beside it, the reverse below the bottom edge (turned as a
              // tablet is turned: about its horizontal axis)
  lithic,     // dorsal face, right profile, ventral face, along the tool's long axis
  two_faces,  // obverse and reverse side by side (a coin, a seal, a plaque: turned about the vertical axis)
  figurine    // front, right side, back
};

/// The object's frame for a layout: `front` the outward normal of the face drawn first (obverse,
/// dorsal, front), `up` up the page in that view. For every layout the front's axis is the
/// surface's least extent (a tablet's and a tool's flattest faces, a figurine's depth); then
/// - tablet: the obverse the flatter face (the scanned one of a scan of one side), up the scan's
///   up within the face unless the face's long axis lies more than 70 degrees from it;
/// - lithic: the dorsal face the less flat (the ventral is the flake's smooth side; the scanned
///   one of a scan of one side), the long axis up, the butt (where the bulk of the surface lies
///   along it) down and the tip up;
/// - the others: default_view's (the side MeshLab shows first, the scan's y up unless the object
///   lies on its side).
/// `turn_over` swaps front and back, `upside_down` turns up down; `how` says what was found.
/// `unscanned`: for a scan of one side (under a tenth of the area facing the front faces the back,
/// or the other way round), the outward direction of the side it lacks (else zero); then `warning`
/// (else empty) says that the layout's views of that side, named "(not scanned)", show its underside.
struct ObjectFrame {
  Vec3 front{0, 0, 1}, up{0, 1, 0};
  std::string how, warning;
  Vec3 unscanned = Vec3::Zero();
};
ObjectFrame object_frame(const TriMesh& mesh, PlateLayout layout, bool turn_over = false, bool upside_down = false);

/// A view of a layout: its name ("obverse", "top edge"...; "reverse (not scanned)" for a view of a
/// scan's unscanned side), its direction and up, and its cell.
/// The first of a layout's views is its main one (the obverse, dorsal face, front): the one a
/// section cuts and a light stack is taken from.
struct LayoutView {
  std::string name;
  PlateView view;
  int column = 0, row = 0;
};
std::vector<LayoutView> layout_views(PlateLayout layout, const ObjectFrame& frame);

/// The plate of a layout: every view of `mesh` (with `layers` and `grey` as make_plate draws
/// them) at one scale (params.ratio, or the largest standard one at which the layout fits A4),
/// each in its cell — a column as wide as its widest view, a row as tall as its tallest, the views
/// centred in them so that views of the same extent line up edge to edge — named below, one
/// scale bar. Throws InputError as make_plate does (curves hidden in a view are no error: an
/// edge view may show none).
/// With `shading`, each view is shaded by plate_shading from its own direction (the light from the
/// page's top left in every view) instead of `grey`.
Plate make_layout_plate(const TriMesh& mesh, const std::vector<double>& grey, const std::vector<PlateCurves>& layers,
                        PlateLayout layout, const ObjectFrame& frame, const PlateParams& params,
                        const PlateShadingParams* shading = nullptr);

/// The same for views of several meshes (the two faces of a coin scanned as two layers): each
/// panel its mesh, shading, curves and view, in its cell.
struct PlatePanel {
  const TriMesh* mesh = nullptr;
  const std::vector<double>* grey = nullptr;  // per vertex of mesh, or empty
  const std::vector<PlateCurves>* layers = nullptr;
  LayoutView view;
};
Plate make_panels_plate(const std::vector<PlatePanel>& panels, const PlateParams& params);

/// One thing drawn on the page (millimetres, y down): the page description both the SVG and the
/// PDF are written from, so that the two cannot draw the plate differently.
struct PageMark {
  enum class Kind { shading, path, text };
  Kind kind = Kind::path;
  std::string group;            // the SVG group it belongs to (a curve layer, "scale bar", "texts")
  std::vector<Vec2> points;     // path: its points (shading: top-left and bottom-right)
  double width_mm = 0;          // path: the stroke's width
  std::vector<double> dashes;   // path: dash and gap lengths in mm (empty: solid)
  bool round_caps = true;       // path: round caps and joins (false: flat caps, for dashes)
  bool filled = false;          // path: closed and filled black
  std::string text;             // text: what it says, its baseline's anchor at points[0]
  double size_mm = 3;           // text: its size
  bool centred = true;          // text: anchored at its middle (false: at its start)
};

/// The plate's page: the shading, the paths in their layers, the texts, the scale bar with its
/// label and the scale.
std::vector<PageMark> page_marks(const Plate& plate);

/// The dash-dot pattern of section lines and guides (a long dash, a gap, a dot, a gap), in mm.
const std::vector<double>& dash_dot_mm();

/// Warnings about the plate for the log: an object size no report draws (over 1 m or under 5 mm
/// at the unit given: most likely a wrong unit).
std::vector<std::string> plate_warnings(const Plate& plate, double unit_mm);

/// The plate as an SVG document (millimetre units; the shading embedded as a PNG), from page_marks.
std::string plate_svg(const Plate& plate);

}  // namespace reliefkit
