// ReliefKit — shading among a drawing's curves (issue 23): hatching, cross-hatching and the strokes
// left of stippling are not structure. Left in the region graph, hatching that ends on an outline
// cuts its region into strips and the relief climbs a staircase across a hatched section.
//
// A stroke is shading when it is open and, along most of its length, the ink beside it holds a
// family of near-parallel lines: looking across the stroke both ways, at least two more lines of
// its direction, each within a few line widths of the last (the stroke and its neighbours: three
// lines at least — the two edges of a thin wall are only two). The ink is read, not the curves found
// in it, so hatching the detector broke into pieces still counts; lines of another direction are
// looked through, so each family of a cross-hatching is found on its own. Directions come from the
// structure tensor of the drawing. Closed curves are never shading: outlines, rings and discs stay
// structure, and the lines the shading ends on keep separating their regions.
#pragma once

#include <opencv2/core.hpp>
#include <vector>

#include "reliefkit/drawing/line_drawing.h"

namespace reliefkit {

struct ShadingParams {
  double max_angle = 0.45;         // radians between lines still called parallel (about 25 degrees)
  double max_spacing_widths = 8;   // the next line within this many of the stroke's line widths ...
  double min_spacing_px = 12;      // ... or this many pixels, whichever is more, and half the stroke's length
  double min_hatched_share = 0.5;  // of a stroke's samples that lie in a family of parallel lines
  int min_family = 4;              // lines in a family (the stroke with the lines it sees)
  void validate() const;
};

/// Per curve of `curves` (found in `grey`, drawing_grey, whose `ink` is drawing_ink's): 1 when it is
/// a shading stroke, 0 when it is structure.
std::vector<char> shading_strokes(const cv::Mat& grey, const cv::Mat& ink, const DrawingCurves& curves,
                                  const ShadingParams& params = {});

}  // namespace reliefkit
