#include "reliefkit/base/mesh.h"
#include "reliefkit/base/work_counts.h"

#include "reliefkit/base/memory.h"

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
  count_work(Work::Adjacency);
  VertexFaces vf;
  const int nv = mesh.n_vertices();
  sized(vf.offset, size_t(nv) + 1, 0);
  for (const auto& f : mesh.faces)
    for (int j = 0; j < 3; ++j) ++vf.offset[f[j] + 1];
  for (int v = 0; v < nv; ++v) vf.offset[v + 1] += vf.offset[v];
  sized(vf.face, size_t(vf.offset[nv]));
  sized(vf.corner, size_t(vf.offset[nv]));
  std::vector<int> fill(vf.offset.begin(), vf.offset.end() - 1);
  for (int fi = 0; fi < mesh.n_faces(); ++fi)
    for (int j = 0; j < 3; ++j) {
      int slot = fill[mesh.faces[fi][j]]++;
      vf.face[slot] = fi;
      vf.corner[slot] = static_cast<unsigned char>(j);
    }
  return vf;
}

// One ring of v: the other corners of its faces, each once, in `out` (cleared first). Short rings
// are deduplicated in place; long ones (fans, poles) by sorting, so the cost stays O(d log d).
static void collect_ring(const TriMesh& mesh, const VertexFaces& vf, int v, std::vector<int>& out) {
  out.clear();
  const int faces = vf.offset[v + 1] - vf.offset[v];
  for (int k = vf.offset[v]; k < vf.offset[v + 1]; ++k) {
    const auto& f = mesh.faces[vf.face[k]];
    const int c = vf.corner[k];
    for (int u : {f[(c + 1) % 3], f[(c + 2) % 3]}) {
      if (u == v) continue;
      if (faces <= 16) {
        bool seen = false;
        for (int w : out) seen = seen || w == u;
        if (!seen) out.push_back(u);
      } else {
        out.push_back(u);
      }
    }
  }
  if (faces > 16) {
    std::sort(out.begin(), out.end());
    out.erase(std::unique(out.begin(), out.end()), out.end());
  }
}

VertexRing vertex_rings(const TriMesh& mesh, const VertexFaces& vf) {
  VertexRing r;
  const int nv = mesh.n_vertices();
  sized(r.offset, size_t(nv) + 1);
#pragma omp parallel
  {
    std::vector<int> tmp;
#pragma omp for schedule(dynamic, 4096)
    for (int v = 0; v < nv; ++v) {
      collect_ring(mesh, vf, v, tmp);
      r.offset[v + 1] = static_cast<int>(tmp.size());
    }
  }
  for (int v = 0; v < nv; ++v) r.offset[v + 1] += r.offset[v];
  sized(r.vertex, size_t(r.offset[nv]));
#pragma omp parallel
  {
    std::vector<int> tmp;
#pragma omp for schedule(dynamic, 4096)
    for (int v = 0; v < nv; ++v) {
      collect_ring(mesh, vf, v, tmp);
      std::copy(tmp.begin(), tmp.end(), r.vertex.begin() + r.offset[v]);
    }
  }
  return r;
}

// The neighbours of v across boundary edges, ascending, in `out`: among the other corners of v's
// faces, an edge with one face appears once. `others` is scratch space.
static void collect_boundary_neighbours(const TriMesh& mesh, const VertexFaces& vf, int v, std::vector<int>& others,
                                        std::vector<int>& out) {
  others.clear();
  out.clear();
  for (int k = vf.offset[v]; k < vf.offset[v + 1]; ++k) {
    const auto& f = mesh.faces[vf.face[k]];
    const int c = vf.corner[k];
    for (int u : {f[(c + 1) % 3], f[(c + 2) % 3]})
      if (u != v) others.push_back(u);
  }
  std::sort(others.begin(), others.end());  // O(d log d): fans of 100,000 faces stay cheap
  for (size_t i = 0; i < others.size();) {
    size_t j = i;
    while (j < others.size() && others[j] == others[i]) ++j;
    if (j - i == 1) out.push_back(others[i]);
    i = j;
  }
}

// Counted, then filled in place: no list per vertex (half a million small allocations cost more
// than sorting each vertex's corners twice).
VertexRing boundary_rings(const TriMesh& mesh, const VertexFaces& vf) {
  const int nv = mesh.n_vertices();
  VertexRing r;
  r.offset.assign(nv + 1, 0);
#pragma omp parallel
  {
    std::vector<int> others, nb;
#pragma omp for schedule(dynamic, 4096)
    for (int v = 0; v < nv; ++v) {
      collect_boundary_neighbours(mesh, vf, v, others, nb);
      r.offset[v + 1] = static_cast<int>(nb.size());
    }
  }
  for (int v = 0; v < nv; ++v) r.offset[v + 1] += r.offset[v];
  r.vertex.resize(size_t(r.offset[nv]));
#pragma omp parallel
  {
    std::vector<int> others, nb;
#pragma omp for schedule(dynamic, 4096)
    for (int v = 0; v < nv; ++v) {
      if (r.offset[v + 1] == r.offset[v]) continue;
      collect_boundary_neighbours(mesh, vf, v, others, nb);
      std::copy(nb.begin(), nb.end(), r.vertex.begin() + r.offset[v]);
    }
  }
  return r;
}

MeshTopology mesh_topology(const TriMesh& mesh) { return mesh_topology(mesh, vertex_faces(mesh)); }

MeshTopology mesh_topology(const TriMesh& mesh, VertexFaces faces) {
  MeshTopology t;
  t.faces = std::move(faces);
  t.ring = vertex_rings(mesh, t.faces);
  t.border = boundary_rings(mesh, t.faces);
  return t;
}

std::vector<MeshEdge> mesh_edges(const TriMesh& mesh, const VertexFaces& vf) {
  std::vector<MeshEdge> edges;
  std::vector<std::pair<int, int>> other;  // (b, face) of a's faces, b > a; faces in increasing order
  for (int a = 0; a < mesh.n_vertices(); ++a) {
    other.clear();
    for (int k = vf.offset[a]; k < vf.offset[a + 1]; ++k) {
      const auto& f = mesh.faces[vf.face[k]];
      const int c = vf.corner[k];
      for (int b : {f[(c + 1) % 3], f[(c + 2) % 3]})
        if (b > a) other.push_back({b, vf.face[k]});
    }
    std::stable_sort(other.begin(), other.end(), [](const auto& x, const auto& y) { return x.first < y.first; });
    for (size_t i = 0; i < other.size();) {
      MeshEdge e;
      e.a = a;
      e.b = other[i].first;
      for (; i < other.size() && other[i].first == e.b; ++i) {
        if (e.faces < 2) e.face[size_t(e.faces)] = other[i].second;
        ++e.faces;
      }
      edges.push_back(e);
    }
  }
  return edges;
}

}  // namespace reliefkit
