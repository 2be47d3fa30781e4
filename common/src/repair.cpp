#include "reliefkit/repair.h"

#include <algorithm>
#include <array>
#include <numeric>
#include <sstream>
#include <tuple>

namespace reliefkit {

std::string RepairReport::summary() const {
  if (!changed() && conflicting_parts == 0) return "";
  std::ostringstream s;
  s << "Repaired for the computation (the layer itself is unchanged):";
  const char* sep = " ";
  auto item = [&](long long n, const char* one, const char* many) {
    if (n > 0) s << sep << n << " " << (n == 1 ? one : many), sep = "; ";
  };
  item(welded_vertices, "coincident vertex welded", "coincident vertices welded");
  item(duplicate_faces, "duplicated face ignored", "duplicated faces ignored");
  item(collapsed_faces, "face collapsed by welding ignored", "faces collapsed by welding ignored");
  item(flipped_faces, "face flipped to agree with its neighbours", "faces flipped to agree with their neighbours");
  item(reversed_parts, "closed part turned outside out", "closed parts turned outside out");
  if (conflicting_parts > 0)
    s << sep << conflicting_parts
      << " parts cannot be oriented coherently (Moebius-like; run Filters > Cleaning and Repairing > Re-Orient all "
         "faces coherentely to see where)";
  s << ".";
  return s.str();
}

RepairedMesh repair_for_computation(const TriMesh& in) {
  RepairedMesh out;
  RepairReport& rep = out.report;
  const int nv = in.n_vertices();
  // A face referring to a missing vertex is not repairable here: return the mesh as it is, for
  // require_triangles() to refuse with its message.
  for (const auto& f : in.faces)
    for (int v : f)
      if (v < 0 || v >= nv) {
        out.mesh = in;
        out.of_input.resize(nv);
        std::iota(out.of_input.begin(), out.of_input.end(), 0);
        return out;
      }

  // 1. Weld vertices at exactly the same position (sort by coordinates).
  std::vector<int> order(nv);
  std::iota(order.begin(), order.end(), 0);
  auto less = [&](int a, int b) {
    const Vec3 &p = in.vertices[a], &q = in.vertices[b];
    return std::tie(p.x(), p.y(), p.z(), a) < std::tie(q.x(), q.y(), q.z(), b);
  };
  std::sort(order.begin(), order.end(), less);
  out.of_input.assign(nv, -1);
  for (int i = 0; i < nv; ++i) {
    const int v = order[i];
    if (i > 0 && in.vertices[v] == in.vertices[order[i - 1]] && in.vertices[v].allFinite()) {
      out.of_input[v] = out.of_input[order[i - 1]];
      ++rep.welded_vertices;
    } else {
      out.of_input[v] = static_cast<int>(out.mesh.vertices.size());
      out.mesh.vertices.push_back(in.vertices[v]);
    }
  }
  // Keep the repaired vertices in input order where nothing was welded (stable results).
  if (rep.welded_vertices == 0) {
    out.mesh.vertices = in.vertices;
    std::iota(out.of_input.begin(), out.of_input.end(), 0);
  }

  // 2. Faces on the welded vertices; drop collapsed and duplicated ones.
  std::vector<std::array<int, 3>> faces;
  faces.reserve(in.faces.size());
  for (const auto& f : in.faces) {
    if (f[0] < 0 || f[1] < 0 || f[2] < 0 || f[0] >= nv || f[1] >= nv || f[2] >= nv) {
      faces.push_back(f);  // left for require_triangles() to refuse
      continue;
    }
    std::array<int, 3> g{out.of_input[f[0]], out.of_input[f[1]], out.of_input[f[2]]};
    if (rep.welded_vertices > 0 && (g[0] == g[1] || g[1] == g[2] || g[0] == g[2])) {
      ++rep.collapsed_faces;
      continue;
    }
    faces.push_back(g);
  }
  {
    // Duplicates share all three vertices: look among the faces of the face's vertex of least
    // valence (no global sort; linear in the faces even around a vertex of very high valence).
    TriMesh tmp;
    tmp.faces = faces;
    tmp.vertices.resize(out.mesh.vertices.size());
    const VertexFaces vf = vertex_faces(tmp);
    auto deg = [&](int v) { return vf.offset[v + 1] - vf.offset[v]; };
    const int nff = static_cast<int>(faces.size());
    std::vector<char> drop(faces.size(), 0);
#pragma omp parallel for schedule(dynamic, 4096)
    for (int i = 0; i < nff; ++i) {
      const auto& t = faces[i];
      if (t[0] < 0 || t[0] == t[1] || t[1] == t[2] || t[0] == t[2]) continue;
      int c = t[0];
      for (int v : t)
        if (deg(v) < deg(c)) c = v;
      auto key = t;
      std::sort(key.begin(), key.end());
      for (int k = vf.offset[c]; k < vf.offset[c + 1]; ++k) {
        const int g = vf.face[k];
        if (g >= i) continue;  // an earlier face on the same vertices makes this one a duplicate
        auto kg = faces[g];
        std::sort(kg.begin(), kg.end());
        if (kg == key) {
          drop[i] = 1;
          break;
        }
      }
    }
    for (size_t i = 0; i < faces.size(); ++i) {
      if (drop[i])
        ++rep.duplicate_faces;
      else
        out.mesh.faces.push_back(faces[i]);
    }
  }

  // 3. Coherent orientation per part: breadth-first over manifold edges (exactly two faces). The
  // face across an edge is found among the faces of the edge's end of least valence.
  const int nf = out.mesh.n_faces();
  const VertexFaces vf = vertex_faces(out.mesh);
  auto deg = [&](int v) { return vf.offset[v + 1] - vf.offset[v]; };
  // Per face and side: the neighbour across it (-1: boundary or non-manifold) and whether the two
  // traverse the edge in the same direction (then one of them must be flipped).
  std::vector<std::array<int, 3>> across(nf, {-1, -1, -1});
  std::vector<std::array<char, 3>> same_dir(nf, {0, 0, 0});
  std::vector<char> closed_edge_ok(nf, 1);  // every edge of the face has exactly two faces
#pragma omp parallel for schedule(dynamic, 4096)
  for (int f = 0; f < nf; ++f) {
    const auto& t = out.mesh.faces[f];
    for (int j = 0; j < 3; ++j) {
      const int a = t[j], b = t[(j + 1) % 3];
      if (a == b) {
        closed_edge_ok[f] = 0;
        continue;
      }
      const int c = deg(a) <= deg(b) ? a : b;
      int found = -1, count = 0;
      char same = 0;
      for (int k = vf.offset[c]; k < vf.offset[c + 1]; ++k) {
        const int g = vf.face[k];
        if (g == f) continue;
        const auto& u = out.mesh.faces[g];
        for (int i = 0; i < 3; ++i) {
          if (u[i] == a && u[(i + 1) % 3] == b) ++count, found = g, same = 1;
          if (u[i] == b && u[(i + 1) % 3] == a) ++count, found = g, same = 0;
        }
      }
      if (count == 1) {
        across[f][j] = found;
        same_dir[f][j] = same;
      } else {
        closed_edge_ok[f] = 0;
      }
    }
  }
  std::vector<signed char> flip(nf, -1);
  std::vector<int> queue, part;
  for (int seed = 0; seed < nf; ++seed) {
    if (flip[seed] >= 0) continue;
    flip[seed] = 0;
    queue.assign(1, seed);
    part.clear();
    bool conflict = false, closed = true;
    for (size_t q = 0; q < queue.size(); ++q) {
      const int f = queue[q];
      part.push_back(f);
      closed = closed && closed_edge_ok[f];
      for (int j = 0; j < 3; ++j) {
        const int g = across[f][j];
        if (g < 0) continue;
        const signed char want = static_cast<signed char>(flip[f] ^ (same_dir[f][j] ? 1 : 0));
        if (flip[g] < 0) {
          flip[g] = want;
          queue.push_back(g);
        } else if (flip[g] != want) {
          conflict = true;
        }
      }
    }
    if (conflict) {
      ++rep.conflicting_parts;
      for (int f : part) flip[f] = 0;  // not safe to change: leave the part as it was
      continue;
    }
    long long flips = 0;
    for (int f : part) flips += flip[f];
    if (2 * flips > static_cast<long long>(part.size())) {  // keep the majority's orientation
      for (int f : part) flip[f] ^= 1;
      flips = static_cast<long long>(part.size()) - flips;
    }
    rep.flipped_faces += flips;
    if (closed) {  // a closed part: normals outwards (positive signed volume)
      double vol = 0;
      for (int f : part) {
        const auto& t = out.mesh.faces[f];
        double v6 = out.mesh.vertices[t[0]].dot(out.mesh.vertices[t[1]].cross(out.mesh.vertices[t[2]]));
        vol += flip[f] ? -v6 : v6;
      }
      if (vol < 0) {
        for (int f : part) flip[f] ^= 1;
        ++rep.reversed_parts;
      }
    }
    for (int f : part)
      if (flip[f]) std::swap(out.mesh.faces[f][1], out.mesh.faces[f][2]);
  }
  return out;
}

}  // namespace reliefkit
