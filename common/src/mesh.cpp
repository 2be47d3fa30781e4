#include "reliefkit/mesh.h"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace reliefkit {

EdgeStats edge_length_stats(const TriMesh& mesh) {
  EdgeStats s;
  std::vector<float> len;
  len.reserve(mesh.faces.size() * 3);
  for (const auto& f : mesh.faces)
    for (int j = 0; j < 3; ++j) {
      double l = (mesh.vertices[f[j]] - mesh.vertices[f[(j + 1) % 3]]).norm();
      if (std::isfinite(l)) len.push_back(static_cast<float>(l));
    }
  s.count = static_cast<long long>(len.size());
  if (len.empty()) return s;
  double sum = 0;
  for (float l : len) sum += l;
  s.mean = sum / len.size();
  auto mid = len.begin() + len.size() / 2;
  std::nth_element(len.begin(), mid, len.end());
  s.median = *mid;
  auto mm = std::minmax_element(len.begin(), len.end());
  s.min = *mm.first;
  s.max = *mm.second;
  return s;
}

void require_triangles(const TriMesh& mesh) {
  std::ostringstream msg;
  if (mesh.faces.empty()) {
    msg << "The filter needs a triangle mesh, but this layer has "
        << (mesh.vertices.empty() ? std::string("no vertices at all (empty mesh).")
                                  : std::to_string(mesh.vertices.size()) +
                                        " vertices and no faces (a point cloud). Reconstruct a surface first, e.g. "
                                        "Filters > Remeshing > Surface Reconstruction: Screened Poisson.");
    throw InputError(msg.str());
  }
  const int nv = mesh.n_vertices();
  long long bad_index = 0;
  for (const auto& f : mesh.faces)
    for (int j = 0; j < 3; ++j)
      if (f[j] < 0 || f[j] >= nv) ++bad_index;
  if (bad_index) {
    msg << bad_index << " face corners refer to vertices that do not exist.";
    throw InputError(msg.str());
  }
  long long nonfinite = 0;
  for (const auto& p : mesh.vertices)
    if (!p.allFinite()) ++nonfinite;
  if (nonfinite) {
    msg << nonfinite
        << " vertices have invalid (NaN or infinite) coordinates. Remove them first, e.g. "
           "Filters > Cleaning and Repairing > Remove Unreferenced Vertices after deleting the faces that use them.";
    throw InputError(msg.str());
  }
}

VertexFaces vertex_faces(const TriMesh& mesh) {
  VertexFaces vf;
  const int nv = mesh.n_vertices();
  vf.offset.assign(nv + 1, 0);
  for (const auto& f : mesh.faces)
    for (int j = 0; j < 3; ++j) ++vf.offset[f[j] + 1];
  for (int v = 0; v < nv; ++v) vf.offset[v + 1] += vf.offset[v];
  vf.face.resize(vf.offset[nv]);
  vf.corner.resize(vf.offset[nv]);
  std::vector<int> fill(vf.offset.begin(), vf.offset.end() - 1);
  for (int fi = 0; fi < mesh.n_faces(); ++fi)
    for (int j = 0; j < 3; ++j) {
      int slot = fill[mesh.faces[fi][j]]++;
      vf.face[slot] = fi;
      vf.corner[slot] = static_cast<unsigned char>(j);
    }
  return vf;
}

VertexRing vertex_rings(const TriMesh& mesh, const VertexFaces& vf) {
  VertexRing r;
  const int nv = mesh.n_vertices();
  r.offset.assign(nv + 1, 0);
  std::vector<std::vector<int>> tmp;  // per-thread scratch would be faster; rings are small
  std::vector<int> all;
  all.reserve(vf.face.size() * 2);
  std::vector<int> ring;
  for (int v = 0; v < nv; ++v) {
    ring.clear();
    for (int k = vf.offset[v]; k < vf.offset[v + 1]; ++k) {
      const auto& f = mesh.faces[vf.face[k]];
      int c = vf.corner[k];
      ring.push_back(f[(c + 1) % 3]);
      ring.push_back(f[(c + 2) % 3]);
    }
    std::sort(ring.begin(), ring.end());
    ring.erase(std::unique(ring.begin(), ring.end()), ring.end());
    ring.erase(std::remove(ring.begin(), ring.end(), v), ring.end());
    all.insert(all.end(), ring.begin(), ring.end());
    r.offset[v + 1] = static_cast<int>(all.size());
  }
  r.vertex = std::move(all);
  return r;
}

}  // namespace reliefkit
