// ReliefKit — plain indexed triangle mesh used by every algorithm core.
//
// Cores never see MeshLab or Qt types: a plugin (or a test) copies a vcglib mesh into a
// `TriMesh` with reliefkit/base/vcg_adapter.h, runs a core, and writes the results back.
// Positions are in the mesh's own units; faces are counter-clockwise seen from outside, so
// face normals point outwards (the vcglib / MeshLab convention).
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <stdexcept>
#include <string>
#include <vector>

namespace reliefkit {

using Vec3 = Eigen::Vector3d;
using Vec2 = Eigen::Vector2d;
using Mat3 = Eigen::Matrix3d;

struct TriMesh {
  std::vector<Vec3> vertices;              // #V positions
  std::vector<std::array<int, 3>> faces;   // #F vertex-index triples

  int n_vertices() const { return static_cast<int>(vertices.size()); }
  int n_faces() const { return static_cast<int>(faces.size()); }
};

/// Error raised by a core for input it cannot process. The message is written for the
/// user (it says what is wrong and what to do); plugin adapters show it verbatim.
class InputError : public std::runtime_error {
 public:
  explicit InputError(const std::string& what) : std::runtime_error(what) {}
};

/// Progress callback: percent in [0,100] and a short description. Returning false is
/// ignored (cores are not cancellable); a null callback is allowed everywhere.
using Progress = bool (*)(int percent, const char* what);

/// Statistics of a mesh's edges, used to scale parameter defaults.
struct EdgeStats {
  double mean = 0, median = 0, min = 0, max = 0;
  long long count = 0;  // counted once per face side (interior edges twice)
};
EdgeStats edge_length_stats(const TriMesh& mesh);
/// The length unit of parameters is MeshScale::edge (reliefkit/base/scale.h), not these statistics.

/// Checks a mesh before a curvature computation. Throws InputError when the mesh has no
/// faces (empty mesh or point cloud), a face refers to a missing vertex, or a coordinate is
/// not finite. Degenerate faces and non-manifold elements are allowed (cores skip and count
/// them).
void require_triangles(const TriMesh& mesh);

/// Vertex -> incident faces, compressed (CSR) adjacency.
struct VertexFaces {
  std::vector<int> offset;  // #V+1
  std::vector<int> face;    // face ids, offset[v]..offset[v+1]
  std::vector<unsigned char> corner;  // which corner (0..2) of that face is v
};
VertexFaces vertex_faces(const TriMesh& mesh);

/// Vertex -> neighbouring vertices (one ring, each neighbour once), CSR. The ring of a vertex with
/// more than 16 faces is sorted by vertex index (shorter rings are in face order).
struct VertexRing {
  std::vector<int> offset;
  std::vector<int> vertex;
};
VertexRing vertex_rings(const TriMesh& mesh, const VertexFaces& vf);

/// Neighbours of each vertex across boundary edges (edges with one face), CSR; interior
/// vertices have none.
VertexRing boundary_rings(const TriMesh& mesh, const VertexFaces& vf);

/// A mesh's connectivity as the cores use it, built once per run and shared by its stages: the
/// positions may change (pre-smoothing), the connectivity does not.
struct MeshTopology {
  VertexFaces faces;  // vertex -> faces
  VertexRing ring;    // vertex -> neighbours
  VertexRing border;  // vertex -> neighbours across boundary edges
};
MeshTopology mesh_topology(const TriMesh& mesh);
/// The same from the vertex-face adjacency the caller built already.
MeshTopology mesh_topology(const TriMesh& mesh, VertexFaces faces);

/// An edge of the mesh with the faces along it: a < b; `faces` counts them (2 inside a manifold,
/// 1 on the border), `face` holds the first two by index (-1 when there are fewer).
struct MeshEdge {
  int a = 0, b = 0;
  int faces = 0;
  std::array<int, 2> face{-1, -1};
};
/// Every edge once, from the vertex-face adjacency; sorted by (a, b).
std::vector<MeshEdge> mesh_edges(const TriMesh& mesh, const VertexFaces& vf);

}  // namespace reliefkit
