// Synthetic pottery drawings in the half-section convention with a known profile (tests and the
// benchmark of reliefkit/drawing/vessel_profile.h).
#pragma once

#include <opencv2/core.hpp>
#include <vector>

#include "reliefkit/base/mesh.h"

namespace rktest {

enum class SectionStyle { Filled, Outlined, Hatched, ProfileOnly };  // ProfileOnly: the outer line on both sides, no section

struct VesselDrawingOptions {
  SectionStyle style = SectionStyle::Filled;
  bool axis_line = true;   // a thin vertical axis drawn through the vessel
  bool rim = true;         // false: the top is a break below the rim
  bool base = true;        // false: the bottom is a break above the base (the base is missing)
  bool section_left = true;
  int line_px = 2;
  // What a catalogue drawing adds round the vessel (the Bell Beaker case of issue 39):
  bool decorated_sherds = false;  // sherd outlines with cross-hatched bands inside the exterior half
  bool base_drawn_apart = false;  // a base section drawn apart below the vessel (the canvas 200 px taller)
  int label_right = 0;            // a catalogue number this far right of the vessel (the canvas that much wider)
  int second_vessel = 0;          // a smaller half-section this far right (a page of several vessels)
};

/// A jar 420 px high (rim at y = 60, base at y = 480) on a 640 x 560 image, its axis at x = 320:
/// the wall's section (14 px thick, the base too) on one side, the exterior outline on the other,
/// the rim line across the mouth.
struct VesselDrawing {
  cv::Mat image;                         // 8-bit grey
  double axis_x = 320;
  double height = 420;                   // px, of the vessel as drawn (rim or break to base or break)
  double wall = 14;                      // px: the wall's thickness (normal to the wall), base too
  std::vector<reliefkit::Vec2> section;  // the true section in (radius, height = -y), px, closed
  std::vector<reliefkit::Vec2> exterior; // the true outer wall (and base, to the axis), rim to base, open
};
VesselDrawing vessel_drawing(const VesselDrawingOptions& options = {});

/// Distance (same units) from q to the polygon (closed) or polyline (open).
double distance_to_polygon(const reliefkit::Vec2& q, const std::vector<reliefkit::Vec2>& polygon, bool closed = true);

}  // namespace rktest
