// ReliefKit — a coarse copy of a mesh, and values carried from it back to the mesh.
//
// A computation whose result is smooth over the surface (the displacement of a deformation) can
// be made on a coarse copy and carried back: the copy's vertices are connected aggregates of the
// mesh's vertices — a vertex with its still-free neighbours, the aggregation of multilevel.h, about
// 1/7 of the vertices per level — each at its members' mean position, with a face wherever a face
// of the mesh joins three aggregates. Aggregating along the mesh's edges (not in a grid of space)
// keeps apart what is apart on the surface: the two sides of a thin wall, a handle and its body.
#pragma once

#include <Eigen/Sparse>
#include <vector>

#include "reliefkit/base/mesh.h"

namespace reliefkit {

struct CoarseMesh {
  TriMesh mesh;
  std::vector<int> vertex_of;  // per vertex of the fine mesh: its coarse vertex
};

/// Aggregated level after level until at most `most_faces` faces remain (or a level no longer
/// halves the vertices). The fine mesh must pass require_triangles.
CoarseMesh coarsen_mesh(const TriMesh& fine, int most_faces);

/// The interpolation that carries values on the coarse vertices to the fine ones (fine = P coarse):
/// each fine vertex takes a partition-of-unity average of the values of the coarse vertices within
/// r of it that are in a face (r: twice the coarse mesh's mean edge), weighted by (1 - d²/r²)² of their distance d —
/// a smooth function of the position, so the carried field has no steps or kinks. (Coarse vertices
/// near in space but apart on the surface, the two sides of a wall thinner than r, are averaged:
/// a smooth displacement moves both alike.) A fine vertex with none in reach (an unreferenced
/// vertex far from the surface) takes its own coarse vertex's value.
using Interpolation = Eigen::SparseMatrix<double, Eigen::RowMajor>;
Interpolation interpolation_from_coarse(const TriMesh& fine, const CoarseMesh& coarse);

}  // namespace reliefkit
