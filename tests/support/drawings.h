// Synthetic line drawings rendered from known step reliefs, and the measure of a reconstruction
// against them (tests and benchmarks of reliefkit/drawing_*.h).
#pragma once

#include <opencv2/core.hpp>

#include "reliefkit/drawing/drawing_relief.h"

namespace rktest {

/// The nested test drawing at `scale` (1: 600 x 600 px), lines `line_px` wide: an object
/// (rectangle) holding a raised disc, a raised ring with a raised disc inside it (two levels), and
/// a raised rectangle cut in two by a line (touching curves and a junction of three curves).
/// Known levels above the object: disc 1, ring 1, inner disc 2, the rectangle's halves 1 and 2.
cv::Mat nested_drawing(double scale = 1, int line_px = 2);

/// Distance (px) from p to the nearest drawn shape of nested_drawing(scale), and samples every
/// ~1 px along all of them (for recall).
double nested_truth_distance(const reliefkit::Vec2& p, double scale = 1);
std::vector<reliefkit::Vec2> nested_truth_samples(double scale = 1);

/// The level of the part of nested_drawing(scale) at p (image px) as it was drawn: the object 1,
/// the disc and the ring 2, the inner disc 3, the rectangle's halves 2 and 3 (which one is higher
/// the drawing does not say: `right_half_higher`); -1 on the paper around the object or within
/// `clearance` px of a drawn shape.
int nested_true_level(const reliefkit::Vec2& p, bool right_half_higher, double scale = 1, double clearance = 3);

/// Adds shading to a drawing as illustrators do: hatching (short parallel strokes `stroke_px` long,
/// rows 2 x `spacing_px` apart) over the left half of `area`, stippling (dots every `spacing_px`)
/// over its right half; neither must become curves.
void add_shading(cv::Mat& img, cv::Rect area, double stroke_px = 8, double spacing_px = 6);

/// A stone tool as hand drawings show it (issue 23): a heavy closed outline `outline_px` wide, a
/// 3-px line across it ending on the outline at both ends (T-junctions), a scar below it closed by a
/// thin (2 px) line, dense ripple hatching in the tool's upper part and stippling inside the scar, on
/// off-white paper with noise and JPEG compression (q75), 700 x 900 px. Known: the tool's two parts
/// rise (level 1 or more; which stands on which the drawing does not say), the scar stands on its
/// part (one level more). `tool` and `scar` mark their interiors (255), each `clearance` px from its lines.
struct ShadedTool {
  cv::Mat image, tool, scar;
};
ShadedTool shaded_tool_drawing(int outline_px = 8, double clearance = 8);

/// A flake with an 8-px outline whose thin (3 px) scar lines start on it (T-junctions where the
/// outline's detection fades into short pieces), ripple hatching and a stippled cortex; `tool`
/// marks its interior `clearance` px inside the outline (`scar` is empty).
ShadedTool scarred_flake_drawing(double clearance = 8);

/// Sections as excavation reports hatch them (issue 23), 760 x 620 px, 3-px outlines: a lens-shaped
/// section filled with parallel hatching (1-px strokes 9 px apart, ending on its outline); a
/// rectangle cross-hatched (two families 12 px apart crossing at 90 degrees) around a disc left
/// blank, the hatching ending on the disc's outline. Known: `lens` and `rect` rise as wholes (every
/// part of each at one level), `disc` one level above the rectangle; each marks its interior
/// `clearance` px from its lines (`rect` without the disc).
struct HatchedSections {
  cv::Mat image, lens, rect, disc;
};
HatchedSections hatched_sections_drawing(double clearance = 6);

/// Paper texture (Gaussian noise, `sigma` of the white level) and JPEG compression at `quality`.
cv::Mat paper_and_jpeg(const cv::Mat& grey8, double sigma, int quality);

/// Points (image px) inside each known part of nested_drawing(scale): object, disc, ring, inner
/// disc, left and right half of the rectangle.
struct NestedParts {
  cv::Point object, disc, ring, inner, left, right;
};
NestedParts nested_parts(double scale = 1);

/// How well a relief on a drawing_grid matches the regions' levels on its free surface (outside
/// the margins and the paper around the object): the best global scale (height per level) and the
/// RMS error in steps after it.
struct LevelFit {
  double scale = 0, rms_steps = 0;
  long samples = 0;
};
LevelFit fit_levels(const reliefkit::TriMesh& grid, double pixel_size, const reliefkit::DrawingRelief& relief,
                    const reliefkit::DrawingInterpretation& interpretation, cv::Point paper);

/// A relief of nested_drawing(scale) against the levels it was drawn with (nested_true_level), on
/// its free surface (outside the margins; the paper left out): per vertex the height in steps minus
/// the true level. `pixel` gives each vertex's position in the drawing (px); the better of the two
/// readings of the rectangle's halves is taken.
struct TrueLevelError {
  double rms = 0, worst = 0;  // steps
  long samples = 0;
  bool right_half_higher = false;
};
TrueLevelError true_level_error(const std::vector<reliefkit::Vec2>& pixel, const reliefkit::DrawingRelief& relief,
                                double step_height, double scale = 1);

}  // namespace rktest
