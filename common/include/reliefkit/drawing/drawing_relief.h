// ReliefKit — a relief from an interpreted line drawing (thesis section 7.4).
//
// Near every curve (within the margin width w) the relief is a smoothed step across the curve
// from the height of its lower side to that of its higher side (eqs. 7.1-7.3; the sides' heights
// are the regions' topological levels times the step height, so the constants C_p of eq. 7.3 are
// known). Elsewhere the relief is the smoothest surface that meets them: first its Laplacian L,
// L = Delta r in the margins and Delta L = 0 elsewhere (eq. 7.4), then R = r in the margins and
// Delta R = L elsewhere (eq. 7.6) — the bi-Laplacian interpolation keeps the surface between the
// curves curved instead of flat. Both are sparse symmetric positive-definite solves on the free
// vertices (reliefkit/base/solvers.h). Where margins of close curves overlap, a vertex takes the
// profile of its nearest curve.
#pragma once

#include "reliefkit/drawing/drawing_interpretation.h"
#include "reliefkit/base/solvers.h"
#include "reliefkit/base/surface.h"
#include "reliefkit/base/zero_crossings.h"

namespace reliefkit {

struct DrawingReliefParams {
  double margin = 4;          // w, px: the half-width of a step's profile
  double step_height = 1;     // mesh units per level
  double pixel_size = 1;      // mesh units per pixel (image x right, y down -> mesh x right, y up)
  double shading_depth = 0;   // steps: the shading strokes (DrawingInterpretation::shading) cut this deep as fine grooves
  /// Auto: conjugate gradients started from the interpretation's levels (the thesis' speed-up),
  /// CHOLMOD when they do not converge; Direct: CHOLMOD at once (the benchmark's comparison).
  SolverMethod solver = SolverMethod::Auto;
  void validate() const;
};

struct DrawingRelief {
  std::vector<double> height;      // per base vertex, over the base
  std::vector<char> in_margin;     // per base vertex: on a step's profile (a boundary condition)
  std::vector<double> laplacian;   // per base vertex: L of eq. 7.4
  SolveReport laplacian_solve;  // eq. 7.4
  SolveReport relief_solve;      // eq. 7.6 (its last pass)
  long bounded_vertices = 0;     // free vertices held within half a step of their region's level
};

/// The relief (height over the base, per base vertex). Without `pixel_of_vertex` the base lies in
/// the drawing's plane: pixel (px, py) is at (px * pixel_size, -py * pixel_size). With it, it gives
/// each base vertex's position in the drawing (px; NaN where the drawing does not cover the base:
/// height 0 there), e.g. from project_drawing. The Laplacians are the base's own (cotangent, from
/// the run's Surface: a base layer's adjacency is the one its repair built).
DrawingRelief reconstruct_drawing_relief(const Surface& base, const DrawingCurves& curves,
                                         const DrawingInterpretation& interpretation, const DrawingReliefParams& params,
                                         const std::vector<Vec2>* pixel_of_vertex = nullptr);
DrawingRelief reconstruct_drawing_relief(const TriMesh& base, const DrawingCurves& curves,
                                         const DrawingInterpretation& interpretation, const DrawingReliefParams& params,
                                         const std::vector<Vec2>* pixel_of_vertex = nullptr);

/// A drawing laid onto a base mesh by orthographic projection along `view` (towards the base).
struct DrawingProjection {
  std::vector<Vec2> pixel;    // per base vertex: where it is in the drawing (px), NaN where not covered
  Vec3 view = Vec3(0, 0, -1); // the projection direction used
  Vec3 right, up;             // the image's x and -y directions on the base
  double pixel_size = 1;      // mesh units per pixel
  long covered = 0;           // base vertices the drawing covers
  double edge_px = 0;         // median edge length of the covered part, in pixels
};

/// Projects the drawing's `extent` (px) onto the base: along `view`, or (view zero) along the base's
/// axis of least extent, facing the side most of the base's area faces; the extent is scaled
/// uniformly to fit the base's projected bounding box and centred on it, its longer side along the
/// base's longer projected side. A vertex is covered when it faces the viewer and nothing of the
/// base lies in front of it.
DrawingProjection project_drawing(const Surface& base, const cv::Rect& extent, Vec3 view = Vec3(0, 0, 0));
DrawingProjection project_drawing(const TriMesh& base, const cv::Rect& extent, Vec3 view = Vec3(0, 0, 0));
/// Lays the drawing's `extent` on the base in the drawing's own frame: pixel (px, py) at
/// (px, -py) x `pixel_size` in the plane z = 0, seen from +z (the frame of "Vessel from Profile
/// Drawing" and of the plane base), covered as above. For decoration drawn on a vessel's exterior,
/// raised on the vessel made from the same drawing. Throws InputError when it covers nothing.
DrawingProjection project_drawing_as_drawn(const Surface& base, const cv::Rect& extent, double pixel_size);

/// The base's vertices moved along their normals by `height` (normals of the base).
TriMesh displace_along_normals(const Surface& base, const std::vector<double>& height);
TriMesh displace_along_normals(const TriMesh& base, const std::vector<double>& height);

/// A regular grid over pixels [x0, x0 + width - 1] x [y0, y0 + height - 1] of the drawing (one vertex
/// every `cell` px), z = 0: the flat base.
TriMesh drawing_grid(int width, int height, double cell, double pixel_size, int x0 = 0, int y0 = 0);

/// The part of the drawing worth a relief: the curves' bounding box grown by `pad` px, within the image.
cv::Rect drawing_extent(const DrawingCurves& curves, double pad);

/// The base's vertex spacing (px) that resolves a drawing: half the step width, and a quarter of
/// the narrowest region (twice the largest distance from its curves, the 1st percentile over the
/// regions that take part), never below 0.5 px.
double drawing_cell(const DrawingInterpretation& interpretation, double margin);

enum class DrawingBase { Plane, Cylinder };

/// The relief as a surface: the flat grid's vertices raised by `height` along +z (Plane), or the
/// grid rolled round a vertical cylinder whose circumference is the drawing's width (`circumference`,
/// mesh units; image x runs round it, x = `front` faces +z) and raised along the outward normal (Cylinder).
TriMesh relief_surface(const TriMesh& grid, const std::vector<double>& height, DrawingBase base, double circumference,
                       double front = 0);

// ---- the relief's grid as "Relief from Line Drawing" lays it (relief_grid.cpp) --------------

/// The drawn part a relief covers: the curves' bounding box grown by four step widths and 4 px
/// (a step's profile and the free surface beyond it), within the image.
cv::Rect relief_area(const DrawingCurves& curves, double margin);

/// One level's height in mesh units: `percent` of the drawn part's width (`area`, px, at
/// `pixel_size` mesh units per pixel), so that one script suits any DPI and scale.
double relief_step_height(double percent, const cv::Rect& area, double pixel_size);

struct ReliefGridParams {
  double margin = 4;              // px: the step's half-width (Step width)
  double cell = 0;                // px between the grid's vertices; 0: automatic (drawing_cell)
  long max_vertices = 4000000;    // the automatic spacing is coarsened so the grid stays under this
  double pixel_size = 1;          // mesh units per pixel
};

struct ReliefGrid {
  cv::Rect area;                  // px: relief_area
  double cell = 0;                // px between the grid's vertices
  double wanted_cell = 0;         // px: the automatic spacing before coarsening (= cell when none)
  double wanted_vertices = 0;     // the vertices the wanted spacing would have made
  TriMesh grid;                   // drawing_grid over the area, z = 0, mesh units
  std::vector<Vec2> pixel;        // per grid vertex: where it lies in the image (px, y down)
  bool coarsened() const { return cell > wanted_cell; }
};

/// The plane grid a relief on a plane or a cylinder is built on: over relief_area, one vertex every
/// `cell` px (the user's, or drawing_cell's unless the grid would pass max_vertices: then the
/// spacing that fills the area with max_vertices), each vertex's pixel beside it.
ReliefGrid relief_grid(const DrawingCurves& curves, const DrawingInterpretation& interpretation, const ReliefGridParams& params);

// ---- the drawing's curves and levels on the relief (relief_layers.cpp) ---------------------

/// The curves as polylines in the drawing's plane, in mesh units (image x right, y up, z 0; one
/// pixel = `pixel_size`), one segment between successive points; strength = the curve's index.
Polylines drawing_polylines(const DrawingCurves& curves, double pixel_size);

/// The level of the region at each drawing position (px, rounded to the pixel); -1 on a curve,
/// outside the image, or for a NaN position (a vertex the drawing does not cover).
std::vector<double> region_levels(const DrawingInterpretation& interpretation, const std::vector<Vec2>& pixel);

/// The curves on a relief built on a base layer the drawing was projected onto (project_drawing;
/// `relief`: the base displaced, vertex for vertex): each curve point goes to the covered vertex
/// nearest to it in the drawing (found in a hash grid of the covered vertices' pixel positions, cells
/// of two edge lengths), moved within the image plane by what is left of the offset. A point with no
/// covered vertex in its 3 x 3 cells is dropped, with its segments.
Polylines curves_on_projected_relief(const DrawingCurves& curves, const DrawingProjection& projection,
                                     const TriMesh& relief);

/// The curves on a relief built on drawing_grid(area.width, area.height, cell, pixel_size, area.x,
/// area.y) with heights `height`: each curve point at the height of the grid below it (bilinear),
/// then laid on the base like the grid (relief_surface).
Polylines curves_on_grid_relief(const DrawingCurves& curves, double pixel_size, const cv::Rect& area, double cell,
                                const std::vector<double>& height, DrawingBase base, double circumference,
                                double front = 0);

}  // namespace reliefkit
