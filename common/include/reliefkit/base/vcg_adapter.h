// ReliefKit — copying between a vcglib triangle mesh (MeshLab's CMeshO, or a test mesh type)
// and the cores' TriMesh. Deleted vertices and faces are skipped; `vertex_of[i]` maps the
// TriMesh vertex i back to the vcg vertex so results can be written to it.
#pragma once

#include <vcg/complex/complex.h>

#include "reliefkit/base/memory.h"
#include "reliefkit/base/mesh.h"
#include "reliefkit/base/repair.h"

namespace reliefkit {

template <class MeshT>
struct VcgView {
  TriMesh mesh;
  std::vector<typename MeshT::VertexPointer> vertex_of;  // TriMesh index -> vcg vertex
  /// After repair_view: further vcg vertices welded into TriMesh vertex `first`; results are
  /// written to them too.
  std::vector<std::pair<int, typename MeshT::VertexPointer>> also;
  RepairReport repair;
  VertexFaces faces;  // after repair_view: the repaired mesh's vertex-face adjacency (for its Surface)
};

/// Calls f(i, vcg vertex) for every vcg vertex of the view: TriMesh vertex i's own and those
/// welded into it.
template <class MeshT, class F>
void for_each_vertex(const VcgView<MeshT>& view, F f) {
  for (size_t i = 0; i < view.vertex_of.size(); ++i) f(static_cast<int>(i), view.vertex_of[i]);
  for (const auto& [i, v] : view.also) f(i, v);
}

/// Repairs the view's mesh in place (repair_in_place: welded, deduplicated, coherently oriented)
/// and re-maps the vcg vertices.
template <class MeshT>
void repair_view(VcgView<MeshT>& view) {
  std::vector<int> of_input;
  view.repair = repair_in_place(view.mesh, &of_input, &view.faces);
  if (view.repair.welded_vertices == 0) return;  // the vertices are the view's own, in order
  std::vector<typename MeshT::VertexPointer> first(view.mesh.vertices.size(), nullptr);
  view.also.clear();
  for (size_t i = 0; i < view.vertex_of.size(); ++i) {
    const int j = of_input[i];
    if (first[j] == nullptr)
      first[j] = view.vertex_of[i];
    else
      view.also.push_back({j, view.vertex_of[i]});
  }
  view.vertex_of.swap(first);
}

template <class MeshT>
VcgView<MeshT> from_vcg(MeshT& m) {
  VcgView<MeshT> out;
  const long nvert = static_cast<long>(m.vert.size()), nface = static_cast<long>(m.face.size());
  // index[i] = TriMesh index of vcg vertex i (-1 if deleted): a prefix count over live vertices.
  std::vector<int> index;
  sized(index, size_t(nvert), -1);
  int live = 0;
  for (long i = 0; i < nvert; ++i)
    if (!m.vert[i].IsD()) index[i] = live++;
  sized(out.mesh.vertices, size_t(live), Vec3(Vec3::Zero()));
  sized(out.vertex_of, size_t(live), static_cast<typename MeshT::VertexPointer>(nullptr));
#pragma omp parallel for schedule(static)
  for (long i = 0; i < nvert; ++i) {
    auto& v = m.vert[i];
    if (index[i] < 0) continue;
    out.mesh.vertices[index[i]] = Vec3(double(v.P()[0]), double(v.P()[1]), double(v.P()[2]));
    out.vertex_of[index[i]] = &v;
  }
  std::vector<int> face_index;
  sized(face_index, size_t(nface), -1);
  int live_faces = 0;
  for (long i = 0; i < nface; ++i)
    if (!m.face[i].IsD()) face_index[i] = live_faces++;
  sized(out.mesh.faces, size_t(live_faces), std::array<int, 3>{-1, -1, -1});
  auto* base = nvert > 0 ? &m.vert[0] : nullptr;
#pragma omp parallel for schedule(static)
  for (long i = 0; i < nface; ++i) {
    if (face_index[i] < 0) continue;
    auto& f = m.face[i];
    std::array<int, 3> t;
    for (int j = 0; j < 3; ++j) {
      auto* vp = f.V(j);
      long k = (vp == nullptr || base == nullptr) ? -1 : long(vp - base);
      t[j] = (k >= 0 && k < nvert) ? index[k] : -1;
    }
    out.mesh.faces[face_index[i]] = t;
  }
  return out;
}

}  // namespace reliefkit
