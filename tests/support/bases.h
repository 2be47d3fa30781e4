// Drawings of base models for the tests and benchmarks of reliefkit/drawing/base_library.h: a library
// model stood upright in the drawing's world frame, its silhouettes drawn as an excavation
// report's figure (outline in ink, with gaps, hatching inside, a caption beside it, paper noise).
#pragma once

#include <opencv2/core.hpp>
#include <random>

#include "reliefkit/drawing/base_library.h"

namespace rktest {

/// A library model (axis of revolution +z, nozzle +x) in the world frame of a drawing: its axis
/// up (+y), turned by `yaw` degrees about it, mirrored left-right if `mirror`.
reliefkit::TriMesh upright(const reliefkit::TriMesh& model, double yaw_degrees = 0, bool mirror = false);

struct FigureStyle {
  int size = 600;          // image width and height (px)
  int line = 3;            // outline thickness (px)
  int gaps = 2;            // breaks in the outline, each `gap_px` long
  int gap_px = 6;
  bool hatching = true;    // shading strokes inside
  bool caption = true;     // "Fig. 12" beside the drawing
  double noise = 0.06;     // grey noise on the paper
  double scale = 0;        // pixels per unit of the outline; 0: the outline fills 70 % of the image
};
/// The outline (view coordinates, any unit) drawn as an image; `to_px` receives the map from view
/// coordinates to pixels (x' = a x + b, y' = -a y + c as {a, b, c}).
cv::Mat draw_figure(const reliefkit::Outline& outline, const FigureStyle& style, std::mt19937& rng,
                    cv::Vec3d* to_px = nullptr);
/// The same outline in pixels, as draw_figure placed it.
reliefkit::Outline outline_in_pixels(const reliefkit::Outline& outline, const cv::Vec3d& to_px);

/// A figure of a model (upright, as `upright` gives it) in several views, one above the other
/// (`size` x `size` px each, one scale for all): an excavation report's plate.
cv::Mat draw_views(const reliefkit::TriMesh& upright_model, const std::vector<reliefkit::ViewKind>& views,
                   FigureStyle style, std::mt19937& rng);

/// A goblet's front outline (thesis fig. 7.8 / 7.10): a cup on a stem on a foot, 1 unit tall.
reliefkit::Outline goblet_outline();

}  // namespace rktest
