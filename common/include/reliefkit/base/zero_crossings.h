// ReliefKit — zero crossings of a per-vertex function taken along a per-vertex direction field.
//
// Demarcating curves (k(g_p) = 0), ridges and valleys (d k1 / d t1 = 0) and relief edges all
// are loci where a function f(p, t(p)) changes sign, f being evaluated in a direction t that
// varies from vertex to vertex. Following thesis section 3.3.2 (after DeCarlo et al. and
// Ohtake et al.), each face is examined with its three vertex directions:
//  * if all three pairs of directions are within `max_angle` (pi/4), each vertex keeps its own
//    value f(v, t_v);
//  * otherwise, if a pair agrees, the mean of that pair's directions is rotated into the tangent
//    plane of the third vertex and f is re-evaluated there in that direction;
//  * otherwise the face is dropped (counted in `rejected_faces`).
// On each edge whose end values differ in sign the crossing point is placed by linear
// interpolation, and the two crossing points of a face are joined by a segment. A point's
// strength is interpolated the same way; segments weaker than `min_strength` (mean of their end
// strengths) are dropped. Points on an edge shared by two faces are merged, so segments chain
// into polylines.
// For `axial` fields (principal directions, whose sign is arbitrary) directions are first
// flipped to agree with the face's first vertex, and f is re-evaluated on the flipped ones.
#pragma once

#include <functional>
#include <limits>

#include "reliefkit/base/mesh.h"

namespace reliefkit {

struct DirectionalField {
  std::vector<Vec3> direction;  // #V unit tangent directions t(v)
  std::vector<double> value;    // #V f(v, t(v))
  std::vector<double> strength; // #V strength s(v, t(v)) (may be empty: all points strength 0)
  bool axial = false;           // direction and its opposite are the same (sign is arbitrary)
  /// f(v, t) for another tangent direction t at v. Required.
  std::function<double(int, const Vec3&)> value_along;
  /// s(v, t); when empty, strength[v] is used unchanged.
  std::function<double(int, const Vec3&)> strength_along;
};

/// The same field, borrowed: pointers to #V arrays owned elsewhere (no copies of large arrays).
struct DirectionalFieldView {
  const Vec3* direction = nullptr;
  const double* value = nullptr;
  const double* strength = nullptr;  // may be null
  size_t size = 0;
  bool axial = false;
  std::function<double(int, const Vec3&)> value_along;
  std::function<double(int, const Vec3&)> strength_along;
};
DirectionalFieldView view_of(const DirectionalField& field);

struct ZeroCrossingOptions {
  double max_angle = 0.78539816339744831;  // pi/4 (thesis 3.3.2)
  double min_strength = -std::numeric_limits<double>::infinity();
  /// Optional extra test of a crossed face: face id, the three vertex values and directions
  /// used (after the consistency rule). Ridges use it to keep maxima and drop minima.
  std::function<bool(int face, const double value[3], const Vec3 direction[3])> accept_face;
};

struct Polylines {
  std::vector<Vec3> points;                  // curve points, on mesh edges
  std::vector<double> strength;              // per point
  std::vector<std::array<int, 2>> point_edge;  // per point: the mesh edge (a < b) it lies on
  std::vector<double> point_weight;          // per point: position = (1 - w) a + w b
  std::vector<std::array<int, 2>> segments;  // pairs of point indices, one per crossed face
  std::vector<int> segment_face;             // face of each segment
  long long rejected_faces = 0;              // faces dropped by the direction-consistency rule

  double total_length() const;
  /// Chains segments into maximal polylines (point index lists; closed loops repeat their first
  /// point at the end). Branch points (degree > 2, only on non-manifold input) end chains.
  std::vector<std::vector<int>> chains() const;  // chain_segments(points, segments)
};

/// Segments (pairs of indices into `n_points` points) chained into maximal polylines of point
/// indices: open chains from each point of degree other than 2, then the closed loops (their first
/// point repeated at the end). Branch points end chains.
std::vector<std::vector<int>> chain_segments(int n_points, const std::vector<std::array<int, 2>>& segments);

/// Throws InputError if the field's sizes do not match the mesh.
Polylines extract_zero_crossings(const TriMesh& mesh, const std::vector<Vec3>& normals,
                                 const DirectionalFieldView& field, const ZeroCrossingOptions& options = {});

/// The mesh cut by the plane {p : p · normal = offset} (the zero crossings of the signed distance
/// to it: every face is consistent and no point is moved); `normal` unit.
Polylines plane_cut(const TriMesh& mesh, const Vec3& normal, double offset);
Polylines extract_zero_crossings(const TriMesh& mesh, const std::vector<Vec3>& normals,
                                 const DirectionalField& field, const ZeroCrossingOptions& options = {});

/// The crossings at `min_strength` and above, and the strength of every crossed face's segment,
/// also of those below it: the distribution an automatic threshold needs, without building (and
/// merging) the weak segments.
struct CandidateCrossings {
  Polylines lines;
  std::vector<double> all_strengths;  // one per crossed face that passed the direction and accept tests
};
CandidateCrossings extract_candidate_crossings(const TriMesh& mesh, const std::vector<Vec3>& normals,
                                               const DirectionalFieldView& field, const ZeroCrossingOptions& options);

/// The gradient over a face of the linear interpolation of three values at its corners (zero on
/// a degenerate face): accept_face tests use it to tell maxima from minima.
Vec3 face_gradient(const TriMesh& mesh, int face, const double value[3]);

/// Linear interpolation of a per-vertex quantity at the curve points.
std::vector<double> interpolate_at_points(const Polylines& curves, const std::vector<double>& per_vertex);

}  // namespace reliefkit
