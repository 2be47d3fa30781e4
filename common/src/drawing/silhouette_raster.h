// ReliefKit — what the four parts of the base from silhouettes (base_library.h) share and
// no caller needs: the signed axes of a view, a mesh's projection as a raster, its outer contour,
// densely sampled outlines. Private to common/src/drawing.
#pragma once

#include <functional>
#include <opencv2/core.hpp>
#include <string>

#include "reliefkit/drawing/base_library.h"

namespace reliefkit::silhouette {

/// Signed world axes (+1..+3, -1..-3 for x, y, z and their negatives) of a view's two coordinates.
std::array<int, 2> view_axes(ViewKind view);
std::string lower(std::string s);
/// Points along the closed polygon at most `step` apart.
std::vector<Vec2> densify(const Outline& o, double step);

/// A mesh's orthographic projection onto two signed world axes, as a filled mask.
struct Raster {
  cv::Mat mask;       // CV_8U, 255 inside the projection (holes filled), zero border
  double a0 = 0, b1 = 0, scale = 1, pad = 2;
  std::array<int, 2> axes{1, 2};
  Vec2 to_pixel(const Vec2& ab) const { return Vec2(pad + (ab.x() - a0) * scale, pad + (b1 - ab.y()) * scale); }
  Vec2 to_world(double x, double y) const { return Vec2(a0 + (x - pad) / scale, b1 - (y - pad) / scale); }
};
/// `resolution` pixels across the larger extent; an empty mask for an empty projection.
Raster rasterize(const TriMesh& mesh, int u, int v, int resolution);
/// The outer contour of the mask's largest body, each pixel taken through `to`.
Outline largest_contour(const cv::Mat& mask, const std::function<Vec2(double, double)>& to);
/// The raster's largest contour in world units.
Outline raster_outline(const Raster& r);

}  // namespace reliefkit::silhouette
