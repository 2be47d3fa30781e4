// ReliefKit — interpreting a line drawing: which side of each curve is higher, by how many steps
// (thesis section 7.3).
//
// The curves cut the drawing into regions; the thesis' margins are the regions' borders along the
// curves, so here the graph's nodes are the regions and each curve is an edge between the regions
// on its two sides. A curve between two regions becomes a step from the lower to the higher one:
// the graph is directed acyclically (a total order of the regions: breadth-first from the base
// regions — the thesis' heuristic: the regions with the most curves, so that reliefs rise from the
// base — or from regions whose directions the user fixed), and each region's height is its
// topological level (the longest chain of steps below it); a curve's step is the difference of
// the heights of its two sides. Integer, positive, consistent along every path (Constraints 1-3).
#pragma once

#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "reliefkit/drawing/line_drawing.h"

namespace reliefkit {

/// A curve's cross-section (thesis fig. 7.12, sect. 7.7): a step between its two sides, or a thin
/// ridge or valley on top of whatever step there is (alone, it leaves both sides at one height and
/// acts only within its margin).
enum class CurveProfile { Step, Ridge, Valley };

/// The profile of one stretch of a curve, from arc-length fraction `from` to `to` (0: the curve's
/// start, 1: its end). Across the curve, t in [-1, 1] is the signed distance over the step width
/// (negative on the curve's left, seen along it with image y down). The relief there is
///   h_left + (h_right - h_left) S(t) + A B(t),
/// S the step's shape (0 to 1), B the bump of a ridge (A > 0) or valley (A < 0, both 0 at t = +-1).
/// `shape` (free form): samples (t, value) of S for a step, of B for a ridge / valley, with t
/// increasing; empty: the built-in smooth step and bump.
struct ProfileSpan {
  double from = 0, to = 1;
  CurveProfile profile = CurveProfile::Step;
  std::vector<Vec2> shape;
};

/// What the user says about one curve (the thesis' fine-tuning, Constraints 3 and 4, and its
/// several free-form profiles per curve). Direction: which side is lower.
struct CurveOverride {
  enum class Direction { Auto, LeftLower, RightLower };
  int curve = -1;
  Direction direction = Direction::Auto;
  int weight = 0;  // a step: at least this many levels (0: automatic, 1); a ridge / valley: its height in levels
  std::vector<ProfileSpan> spans;  // empty: one step along the whole curve
  /// A step separates two levels unless every span is a ridge or valley.
  bool is_step() const;
};

struct InterpretationParams {
  double margin = 3;  // px: how far beside a curve its two sides are sampled
  double gap_close = 8;  // px: curve ends are extended this far to close junction gaps
  double min_region_area = 400;  // px^2: smaller regions (between dots of stippling, strokes of hatching) take no part
  bool paper_is_base = true;     // the regions touching the image border are the ground (level 0)
  std::vector<CurveOverride> overrides;
  void validate() const;
};

struct DrawingInterpretation {
  cv::Mat regions;                    // CV_32S, region label per pixel (-1 on the curves)
  int region_count = 0;
  std::vector<std::array<int, 2>> sides;  // per curve: the region on its left and on its right (-1 unknown)
  std::vector<int> region_height;     // topological level of each region (0: the base)
  std::vector<int> step;              // per curve: height(right) - height(left), 0 when not a step
  std::vector<int> base_regions;      // the regions the base heuristic chose (or level 0)
  std::vector<std::vector<ProfileSpan>> profiles;  // per curve (empty: a step along the whole curve)
  std::vector<char> is_step;          // per curve: separates two levels (not only ridges / valleys)
  std::vector<int> weight;            // per curve: the override's weight (0 automatic)
  int ignored_curves = 0;             // curves with the same region (or none) on both sides (shading aside)
  std::vector<char> shading;          // per curve: a shading stroke (DrawingCurves::shading), not in the regions
  int shading_curves = 0;
};

/// Regions, sides and levels of the curves of a drawing. Throws InputError when the overrides'
/// directions contradict each other (a cycle), or name unknown curves or the same curve twice.
DrawingInterpretation interpret_drawing(const DrawingCurves& curves, const InterpretationParams& params = {});

/// The regions above the ground (level > 0).
int rising_regions(const DrawingInterpretation& di);

/// A drawn object part of whose inside stays at the ground's level.
struct FlatObject {
  cv::Rect box;             // px
  double flat_share = 0;    // of its inside (off the curves) in level-0 regions
};
/// The drawn objects (DrawingCurves::objects of 400 px^2 and 2 % of the largest or more: labels and
/// marks aside) whose inside lies in level-0 regions
/// over more than `min_share` of it: their outline is open to the paper where the curves left a gap
/// (or they have an opening). Empty when the objects are not known (no outline completion).
std::vector<FlatObject> flat_objects(const DrawingCurves& curves, const DrawingInterpretation& di, double min_share = 0.1);

/// A relief needs a region above the ground. Throws InputError when none rises, saying what the
/// drawing gave (curves, regions, curves between no two regions) and what to change — a flat
/// plane is never returned as a relief. `line_scale_px`: the line scale the curves were found at.
void require_rising_regions(const DrawingCurves& curves, const DrawingInterpretation& di, double line_scale_px);

}  // namespace reliefkit
