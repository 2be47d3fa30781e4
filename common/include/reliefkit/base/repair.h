// ReliefKit — repairs a copy of a scan for the computation, where the repair is safe.
//
// Exporters and scanners deliver meshes that are the right surface in the wrong form: a triangle
// soup with every vertex repeated per face (STL), faces listed twice, faces with inconsistent
// orientation. Curvature on such meshes is silently wrong (zero on a soup, sign-flipped on
// flipped faces). repair_for_computation() returns a repaired copy and the map back to the input's
// vertices; the filters compute on the copy and write results to every input vertex, so the
// user's mesh is left as it was. Every repair is counted, for the log.
#pragma once

#include <string>

#include "reliefkit/base/mesh.h"

namespace reliefkit {

struct RepairReport {
  long long welded_vertices = 0;   // input vertices merged into another at the same position
  long long duplicate_faces = 0;   // faces on the same three vertices as an earlier face (dropped)
  long long collapsed_faces = 0;   // faces left with a repeated vertex after welding (dropped)
  long long flipped_faces = 0;     // faces turned to agree with their neighbours' orientation
  int reversed_parts = 0;          // closed parts turned inside out (normals now point outwards)
  int conflicting_parts = 0;       // parts whose orientation cannot be made coherent (Moebius-like)
  bool changed() const {
    return welded_vertices || duplicate_faces || collapsed_faces || flipped_faces || reversed_parts;
  }
  /// One sentence for the log ("" when nothing was repaired).
  std::string summary() const;
};

struct RepairedMesh {
  TriMesh mesh;
  std::vector<int> of_input;  // #V input: the repaired vertex each input vertex became
  RepairReport report;
};

/// Welds vertices at exactly the same position, drops duplicated and collapsed faces, and makes
/// the orientation coherent per connected part (keeping the orientation most of the part's faces
/// had; a closed part is turned so that its normals point outwards). Non-finite coordinates are
/// left to require_triangles() to refuse.
RepairedMesh repair_for_computation(const TriMesh& mesh);

/// The same on the mesh itself (no copy: what the MeshLab adapter uses on its own copy of the
/// layer). `of_input` (optional) receives the input-vertex -> repaired-vertex map; `faces`
/// (optional) the repaired mesh's vertex-face adjacency, which the repair builds anyway (a
/// Surface takes it, so that a run builds the adjacency once).
RepairReport repair_in_place(TriMesh& mesh, std::vector<int>* of_input, VertexFaces* faces = nullptr);

}  // namespace reliefkit
