// ReliefKit — a wheel-made vessel from its profile drawing (issue 23; the pottery convention of
// excavation reports, not a chapter of the thesis).
//
// A pottery drawing is a half-section: a vertical axis; on one side the wall's section (filled
// black, hatched, or a closed outline), on the other the exterior. The section is the cross-section
// of the wall in any plane through the axis, so revolving its boundary around the axis gives the
// vessel — outer wall, inner wall, rim and base — exactly; where the drawing ends at a break (a
// missing base or rim) the revolved wall ends there too, nothing is invented.
//
// Reading the drawing: the ink (Otsu's threshold) without specks (stippling, dust); the pen width
// (the median width of the strokes); the vessel's piece of the drawing (a large connected drawing
// with what lies beside it and what mirrors it, the one mirroring best — a frame round a figure
// panel, a base section drawn apart below, labels and further vessels on the page are left out and
// counted; when it is no vessel profile, the next is tried); the axis (the line
// about which the piece's outer edges mirror, row by row — a half-section's exterior mirrors its
// section — taken at a drawn vertical line there when there is one; else the longest drawn
// vertical line near the middle, else that middle); the section: among the closed regions between
// strokes (outlined sections), the solid ink (filled sections) and the ink with its hatching closed
// (hatched sections), the region lying on one side of the axis that borders the paper around the
// vessel over the longest stretch for its thickness — a wall is long and thin. When no region
// qualifies (a profile drawn as one line), the outermost line on the side is the outer wall alone.
//
// Coordinates: pixels of the image, x right, y down; the vessel in mesh units, the drawing's plane
// z = 0 (pixel (px, py) at (px, -py) x pixel_size, as the other drawing filters place it), the axis
// vertical through x = axis_x, the section's side of the drawing at angle pi (left) or 0 (right).
#pragma once

#include <limits>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "reliefkit/base/mesh.h"

namespace reliefkit {

enum class VesselSide { Auto, Left, Right };
enum class VesselAxisSource { Given, DrawnLine, MirroredEdges, MiddleOfDrawing };
enum class VesselSectionKind { Filled, Hatched, Outlined, ProfileLine };

struct VesselParams {
  double axis_x = std::numeric_limits<double>::quiet_NaN();  // px; NaN: found in the drawing
  VesselSide side = VesselSide::Auto;                        // where the section is drawn
  double pixel_size = 1;                                     // mesh units per pixel
  int segments = 0;                                          // around the axis; 0: from the profile's spacing
  /// Throws InputError naming the first parameter out of its range.
  void validate() const;
};

struct VesselProfile {
  std::vector<Vec2> outline;  // px: the section's boundary (closed), or the outer wall top to bottom (ProfileLine)
  bool closed = true;         // outline is a closed polygon
  VesselSectionKind kind = VesselSectionKind::Outlined;
  VesselSide side = VesselSide::Left;
  VesselAxisSource axis_source = VesselAxisSource::Given;
  double axis_x = 0;          // px
  double pen_width = 0;       // px, the median stroke width
  double wall_thickness = 0;  // px: the median width of the section across its medial axis (0 for a profile line)
  double top_y = 0, bottom_y = 0;  // px: the vessel's highest and lowest drawn point
  double rim_radius = 0;      // px: the widest radius in the top tenth of the height
  double max_radius = 0;      // px
  double axis_gap = 0;        // px: the least distance of the wall from the axis (0: the base closes on it)
  double mirrored_rows = 0;   // share of the rows inked on both sides whose outer edges mirror about the axis
  double profile_coverage = 1;  // share of the rows whose outer edges mirror about the axis that the profile spans
  cv::Rect piece;             // px: the part of the drawing read (the vessel's piece)
  int pieces_left_out = 0;    // separate drawings beside it left out (a base drawn apart, labels, other vessels)
  int other_vessels = 0;      // of those, pieces about as large as the vessel's (a page of several vessels)
  bool frame_left_out = false;  // a frame round the figure was left out
  int dash_gaps_joined = 0;     // gaps of dashed lines joined (a wall drawn dashed where it is reconstructed)
  int piece_rank = 0;         // 0: the best candidate piece was the vessel; k: the k before it were no vessel profiles
};

/// What a user must be told of a profile read: lines starting "Warning:" (part of the drawn
/// profile not covered, other vessels on the page) and notes (pieces left out). Empty when none.
std::vector<std::string> vessel_log_lines(const VesselProfile& profile);

/// The vessel's profile read from a drawing (grey, colour or RGBA; dark lines on light paper).
/// Throws InputError saying what was found when the image holds no ink, no axis can be placed, or
/// neither a section nor a profile line lies on the chosen side.
VesselProfile read_vessel_profile(const cv::Mat& image, const VesselParams& params);

/// The vessel: the profile revolved around its axis, `segments` (or, for 0, enough that the widest
/// ring's edges are about as long as the profile's: 48 to 720) around; outward-facing triangles.
/// A closed outline gives a closed surface (a ring of a wall when the base is not drawn).
TriMesh revolve_vessel_profile(const VesselProfile& profile, const VesselParams& params);

/// The profile's outline as resampled for revolve_vessel_profile: (radius, height) in mesh units,
/// height = -py x pixel_size: the outline eased and simplified within 0.5 px (corners kept), its pieces cut to
/// about 1/500 of its length (never shorter than a pen width or 1.5 px).
std::vector<Vec2> vessel_profile_section(const VesselProfile& profile, double pixel_size);

/// One line for a log: axis, side, kind, size in mesh units, mirrored rows, rim and base.
std::string vessel_summary(const VesselProfile& profile, double pixel_size, const char* unit = "mm");

}  // namespace reliefkit
