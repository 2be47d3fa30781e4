// ReliefKit — the plate's view frame, its depth raster, and its visible curves (internal to
// common/src/illustration; see reliefkit/illustration/plate.h).
#pragma once

#include <Eigen/Eigenvalues>
#include <functional>
#include <opencv2/core.hpp>

#include "reliefkit/illustration/plate.h"

namespace reliefkit {

/// The orthographic view on the page: a mesh point's place in millimetres from the drawing's
/// top-left (y down) and its depth along the view (larger: farther).
struct PageFrame {
  Vec3 right, up, ahead;
  double left = 0, top = 0;  // the projection's extreme coordinates (mesh units)
  double nearest = 0, farthest = 0;  // the mesh's extreme depths (mesh units)
  double mm_per_unit = 1;
  Vec2 drawing_mm{0, 0};
  Vec2 to_mm(const Vec3& p) const { return Vec2((p.dot(right) - left) * mm_per_unit, (top - p.dot(up)) * mm_per_unit); }
  double depth(const Vec3& p) const { return p.dot(ahead); }
};

/// The frame at `mm_per_unit` millimetres on the page per mesh unit. Throws InputError when the
/// view sees the mesh as a line or a point (no area).
PageFrame page_frame(const TriMesh& mesh, const PlateView& view, double mm_per_unit);

/// The surface seen from the view at params.dpi: nearest depth per pixel (+inf where there is no
/// surface) and the grey of the surface there (per-vertex grey interpolated, or Lambertian). The
/// scan's small holes — at most 3 mean edge lengths (and at least 2 pixels) across, inside the
/// drawing, where the paper or the surface's back would show as dots — are filled from their rim.
struct DepthRaster {
  cv::Mat depth;  // CV_64F
  cv::Mat grey;   // CV_8U, 255 off the surface
  double px_per_mm = 1;
  double hidden_depth = 0;  // mesh units behind the surface beyond which a curve point is hidden
};
DepthRaster rasterize(const TriMesh& mesh, const std::vector<double>& grey, const PageFrame& frame, const PlateParams& params);

/// The layer's curves (the layer_index-th drawn), chained into polylines, split where they go
/// behind the surface, simplified, weighted (params.weights), appended to plate.paths
/// (millimetres from the drawing's top-left); the segments counted visible or hidden.
void add_visible_paths(Plate& plate, const PlateCurves& layer, int layer_index, const PageFrame& frame,
                       const DepthRaster& raster, const PlateParams& params);

/// The largest standard scale (drawn : real) at which the content (its size in mm at a ratio)
/// fits the page with its margins and scale bar (A4, portrait or landscape, when the page fits the
/// drawing). Throws InputError when it fits at none down to 1:1000.
double standard_ratio(const std::function<Vec2(double)>& content_at, const PlateParams& params);

/// The frame at `ratio` (drawn / real) from the frame at 1:1.
PageFrame at_ratio(PageFrame frame, double ratio);

/// The outline of the surface seen: the edges of its silhouette (the rims of holes through the
/// object too) as closed polylines in millimetres from the drawing's top-left, simplified within
/// `simplify_px` pixels; specks under 16 pixels left out.
std::vector<std::vector<Vec2>> silhouette_outline(const DepthRaster& raster, double simplify_px);

/// A layout's outlines are this many times its curves' width: the heavy pen of the three.
constexpr double kOutlineWeight = 0.5 / 0.35;

/// One view drawn at its frame's scale: the shading raster and the visible curves (millimetres
/// from the view's top-left), the segments counted; with `outline_mm` > 0, the view's outline
/// (silhouette_outline) too, that wide, in the layer "outline".
struct ViewPanel {
  cv::Mat shading;
  std::vector<PlatePath> paths;
  Vec2 size_mm{0, 0};
  long visible = 0, hidden = 0, outside = 0;
};
ViewPanel render_view(const TriMesh& mesh, const std::vector<double>& grey, const std::vector<PlateCurves>& layers,
                      const PageFrame& frame, const PlateParams& params, double outline_mm = 0);

/// An empty page for content of this size: its size (fitted or fixed, InputError when too small)
/// and the content's top-left (drawing_origin_mm), the margins, titles and the bar's room around it.
Plate make_plate_page(const Vec2& content_mm, const PlateParams& params);

/// The scale bar below the content: a round real length (1, 2 or 5 times a power of ten mm) near a
/// quarter of the drawing's width; its label and the scale's.
void add_scale_bar(Plate& plate, double content_height_mm);

/// The room the section's profile takes beside the drawing (to the right, or below), in mm at
/// the frame's scale; zero without a section.
Vec2 section_room_mm(const PageFrame& frame, const PlateParams& params);

/// The mesh cut by the section's plane: its profile appended to plate.paths (layer "section",
/// placed in the room beside the drawing) and the section's line on the drawing (dash-dot).
/// Throws InputError when the plane misses the mesh.
void add_section(Plate& plate, const TriMesh& mesh, const PageFrame& frame, const PlateParams& params);

/// The same for a drawing placed anywhere (a layout's first view): the profile's paths placed with
/// its origin at `profile_at` (a vertical section's depth running right from there, a horizontal
/// one's down) and the line across the drawing whose top-left is `drawing_at`. Nothing without a
/// section.
struct SectionDrawing {
  std::vector<PlatePath> paths;
  long segments = 0;
};
SectionDrawing section_drawing(const TriMesh& mesh, const PageFrame& frame, const PlateParams& params, const Vec2& drawing_at,
                               const Vec2& profile_at);

/// The surface's principal axes: the eigenvectors of the area-weighted covariance of its faces'
/// centroids, eigenvalues ascending (extents a decimated scan's dense patches do not pull).
Eigen::SelfAdjointEigenSolver<Mat3> surface_axes(const TriMesh& mesh);

}  // namespace reliefkit
