// ReliefKit — the curves of a raster line drawing (thesis section 7.2, "pre-processing").
//
// Dark lines are found as in C. Steger, "An unbiased detector of curvilinear structures", PAMI
// 1998 (the thesis' ref. [121]): the image is smoothed by a Gaussian (sigma = 2 px by default); a
// pixel holds a line point where the second derivative across the line (the Hessian's largest
// eigenvalue, positive for a dark line on light paper) is strong, the first derivative across it
// vanishes within the pixel (which is the non-minimum suppression: the line point is the sub-pixel
// minimum of the profile), and the smoothed image is dark there. Line points are linked into
// polylines along the line direction; where a line runs into another one a junction is recorded;
// strokes shorter than a minimum length (shading, stippling, hatching) are dropped.
//
// Images are OpenCV matrices of any depth and 1, 3 or 4 channels; a transparent background (RGBA)
// counts as white paper. Coordinates are pixels, x to the right, y down, (0, 0) the centre of the
// top-left pixel.
#pragma once

#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "reliefkit/base/mesh.h"

namespace reliefkit {

struct LineDetectionParams {
  double sigma = 2.0;          // Gaussian scale, px; 0: automatic, each line at the scale of its width (auto_line_scales)
  double min_strength = 0.01;  // least second derivative across a line, intensity (0-1) / px^2
  double max_intensity = 0.75; // line points are darker than this in the smoothed image (0 black, 1 white)
  double min_length = 12;      // px: shorter strokes are dropped
  double max_link_gap = 1.5;   // px between consecutive line points of one curve
  double max_link_turn = 0.6;  // radians between the directions of consecutive line points
  bool recognise_shading = true;  // flag hatching strokes (DrawingCurves::shading, shading.h)
  double object_gap = 6;       // px: objects' outlines closed over gaps up to twice this (close_object_outlines); 0: none
  /// Throws InputError naming the first parameter out of its range.
  void validate() const;
};

struct DrawingCurves {
  std::vector<std::vector<Vec2>> curves;  // polylines, pixel coordinates
  std::vector<double> line_width;         // per curve: its width class, px (twice the scale it was found at)
  std::vector<char> shading;              // per curve: a stroke of hatching (shading.h), not structure
  std::vector<Vec2> junctions;            // where a curve ends on another one
  int width = 0, height = 0;              // of the image
  long long line_points = 0;              // before linking
  long long dropped_short = 0;            // curves dropped as shorter than min_length
  int outline_pieces = 0;                 // curves added along objects' outlines (close_object_outlines)
  cv::Mat objects;                        // CV_8U, 255 inside a drawn object (its ink closed, holes filled:
                                          // close_object_outlines); empty when not found
  double total_length() const;
};

/// The image as grey levels in [0, 1] (CV_32F), alpha composited on white. Throws InputError for an
/// empty image or an unsupported channel count.
cv::Mat drawing_grey(const cv::Mat& image);

DrawingCurves extract_drawing_curves(const cv::Mat& image, const LineDetectionParams& params = {});

/// The ink of a grey drawing (drawing_grey): darker than Otsu's threshold, never lighter than 0.75
/// of white; 255 on ink (CV_8U).
cv::Mat drawing_ink(const cv::Mat& grey);

/// The widths of the ink's strokes (px), unsorted: at each stroke-centre pixel (a 3 x 3 maximum of
/// the distance transform) twice its distance to the paper, less half a pixel.
std::vector<float> stroke_widths(const cv::Mat& ink);
/// The `share` quantile (0-1) of stroke widths; 0 for none.
double stroke_width_percentile(std::vector<float> widths, double share);

/// A dashed line's dashes joined into one line (a reconstructed wall, a hidden edge): a dash is a
/// stroke (8-connected ink) at most `max_length` px long and 2.5 times as long as it is wide (and as
/// `pen`); each of its ends is drawn (`pen` wide) to the nearest ink ahead of it — within 1.5 dash
/// lengths (at least 4 pens), 20 degrees of its direction — when that ink runs the same way (another
/// dash, or a line's end, within 30 degrees): not to a stroke it points at across. Returns the joins.
int join_dashes(cv::Mat& ink, double pen, double max_length);

/// The scale at which the default threshold min_strength holds; at another scale sigma the
/// threshold is scale-normalised (min_strength x (kReferenceScale / sigma)^2).
constexpr double kReferenceScale = 2.0;
constexpr double kMaxAutoLineScale = 8.0;
/// The scales of automatic detection (sigma = 0): 1, 2, 4, 8 px, up to about half the width of the
/// drawing's widest strokes (their 95th percentile). Each pixel is searched at one of them: the one
/// nearest half the width of the strokes within 2 px (Steger's scale for a bar of width w is at least
/// w / (2 sqrt 3); w / 2 is where the scale-normalised response sigma^2 x the second derivative
/// peaks), so a thick outline and thin hatching are each found at their own scale and a stroke
/// keeps one scale along itself. The strength threshold is scale-normalised.
std::vector<double> auto_line_scales(const cv::Mat& grey);

/// The outlines of the drawn objects where no structure curve runs along them, added as curves (2 px
/// wide); returns how many. An object is the drawing's `ink` (drawing_ink: stippling and shading
/// included) closed over gaps up to 2 x `radius` px, its holes filled: an engraving draws an
/// object's edge with the ends of its hatching, with dots or with a broken line, and without these
/// pieces the object stays open to the paper and cannot rise. `stroke_width`: the drawing's wider
/// strokes (px; the contour runs along the ink's edge, half of it beside a curve that follows it).
int close_object_outlines(DrawingCurves& curves, const cv::Mat& ink, double radius, double stroke_width);

/// The curves whose flag (one per curve, e.g. DrawingCurves::shading) is `value`, with their widths
/// and flags; junctions and counts stay those of the whole drawing.
DrawingCurves curves_where(const DrawingCurves& curves, const std::vector<char>& flag, bool value);

/// Per pixel (CV_32F): the distance to the nearest of the curves whose flag is `value` (drawn as
/// 1-px lines); far everywhere when there is none.
cv::Mat curve_distance(const DrawingCurves& curves, const std::vector<char>& flag, bool value);

/// The margins of the curves (the thesis' fig. 7.2): each curve offset by `width` px to its left and
/// to its right (per point, along the normal of the neighbouring segments), two polylines per curve.
std::vector<std::vector<Vec2>> margin_lines(const DrawingCurves& curves, double width);

/// Largest drawing read at full size (pixels); a larger one is reduced to it (INTER_AREA).
constexpr double kMaxDrawingPixels = 60e6;

/// Reads a drawing (PNG, JPEG, TIFF, BMP, ... : what OpenCV reads) keeping its alpha channel.
/// Throws InputError naming the file when it is missing, unreadable or empty. A drawing larger than
/// kMaxDrawingPixels is reduced; `reduction` (if given) receives the factor (1: read as it is).
cv::Mat read_drawing_image(const std::string& path, double* reduction = nullptr);

}  // namespace reliefkit
