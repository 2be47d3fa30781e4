// ReliefKit — copying between a vcglib triangle mesh (MeshLab's CMeshO, or a test mesh type)
// and the cores' TriMesh. Deleted vertices and faces are skipped; `vertex_of[i]` maps the
// TriMesh vertex i back to the vcg vertex so results can be written to it.
#pragma once

#include <vcg/complex/complex.h>

#include "reliefkit/mesh.h"

namespace reliefkit {

template <class MeshT>
struct VcgView {
  TriMesh mesh;
  std::vector<typename MeshT::VertexPointer> vertex_of;  // TriMesh index -> vcg vertex
};

template <class MeshT>
VcgView<MeshT> from_vcg(MeshT& m) {
  VcgView<MeshT> out;
  std::vector<int> index(m.vert.size(), -1);
  out.mesh.vertices.reserve(m.vn);
  out.vertex_of.reserve(m.vn);
  for (size_t i = 0; i < m.vert.size(); ++i) {
    auto& v = m.vert[i];
    if (v.IsD()) continue;
    index[i] = static_cast<int>(out.mesh.vertices.size());
    out.mesh.vertices.emplace_back(double(v.P()[0]), double(v.P()[1]), double(v.P()[2]));
    out.vertex_of.push_back(&v);
  }
  out.mesh.faces.reserve(m.fn);
  for (auto& f : m.face) {
    if (f.IsD()) continue;
    std::array<int, 3> t;
    for (int j = 0; j < 3; ++j) {
      auto* vp = f.V(j);
      long k = (vp == nullptr) ? -1 : long(vp - &m.vert[0]);
      t[j] = (k >= 0 && k < long(index.size())) ? index[k] : -1;
    }
    out.mesh.faces.push_back(t);
  }
  return out;
}

}  // namespace reliefkit
