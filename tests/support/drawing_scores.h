// Checks of a drawing filter's result that need no annotation (issue 39): the drawing itself says
// what the result must be.
//
// - A relief ("Relief from Line Drawing"): an object's outermost closed outline encloses the
//   object, so its interior must rise and the paper around it stay flat.
// - A vessel ("Vessel from Profile Drawing"): a half-section's exterior outline gives the vessel's
//   radius at every height where both sides are drawn (half the distance between the outer edges).
//
// Both read the drawing with OpenCV alone (Otsu's threshold, a small closing, holes filled): none
// of the filters' own code, so that a filter cannot grade itself. Coordinates: the drawing filters'
// frame, pixel (px, py) at (px, -py) x pixel_mm.
#pragma once

#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "reliefkit/base/mesh.h"

namespace rktest {

/// The drawn objects: the ink closed over 1-px gaps and with every hole filled, as 8-connected
/// components, those of at least `min_share` of the largest one's area (text, specks and arrows
/// left out). A label image (CV_32S, 0 = paper) and their count.
struct DrawnObjects {
  cv::Mat ink;     // CV_8U, 255 = ink (Otsu)
  cv::Mat labels;  // CV_32S: 0 paper, 1..count the objects kept, -1 a small object left out
  int count = 0;
  double pen = 1;  // px: the median stroke width
};
DrawnObjects drawn_objects(const cv::Mat& drawing, double min_share = 0.02);

struct ReliefScore {
  int objects = 0;
  std::vector<double> raised;  // per object: share of its interior at least half a step high
  double paper_flat = 0;       // share of the paper (outside every object) within a quarter step of 0
  double below_paper = 0;      // share of the covered pixels lower than a quarter step below 0
  double uncovered = 0;        // share of the objects' interior the relief does not cover
  double step = 0;             // mesh units
  bool pass = false;
  std::string cause;           // why it fails ("" when it passes)
};

/// `height`: the relief's height over its base per vertex (the layer's vertex quality); the step
/// is 0.5 % of the relief's width (the filter's default, "Step height (% of the drawing's width)").
/// Pass: every object ≥ 0.9 raised, the paper ≥ 0.95 flat, ≤ 0.005 below the paper.
ReliefScore score_relief(const cv::Mat& drawing, const reliefkit::TriMesh& relief, const std::vector<double>& height,
                         double pixel_mm, double step_share = 0.005);

struct VesselScore {
  long rows = 0;            // rows of the vessel's drawing where both sides are drawn
  double coverage = 0;      // share of them at whose height the vessel has a wall
  double median_error = 0;  // |vessel radius - drawn radius| / drawn radius over the covered rows
  double p90_error = 0;
  double drawn_axis = 0;    // px: the drawing's own axis (the exterior's mirror line)
  double vessel_axis = 0;   // px: the vessel's
  bool pass = false;
  std::string cause;
};

/// A vessel's axis (the middle of its extent across: a surface of revolution is symmetric) and its
/// widest radius at each image row (px; NaN where it has no wall), from the edges crossing the row.
struct VesselFrame {
  double axis_x = 0, axis_z = 0;  // mesh units
  std::vector<double> radius;     // per image row
};
VesselFrame vessel_frame(const reliefkit::TriMesh& vessel, double pixel_mm, int rows);

/// Pass: coverage ≥ 0.9, median ≤ 0.02, 90th percentile ≤ 0.05.
VesselScore score_vessel(const cv::Mat& drawing, const reliefkit::TriMesh& vessel, double pixel_mm);

}  // namespace rktest
