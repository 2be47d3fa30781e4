#include "reliefkit/base/repair.h"
#include "reliefkit/base/disjoint_sets.h"
#include "reliefkit/base/memory.h"
#include "reliefkit/base/work_counts.h"

#include <algorithm>
#include <parallel/algorithm>
#include <cstring>
#include <cstdint>
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
  out.mesh = in;
  out.report = repair_in_place(out.mesh, &out.of_input);
  return out;
}

namespace {

// The adjacency's corners after faces were turned (their corners 1 and 2 swapped).
void swap_flipped_corners(const TriMesh& mesh, const std::vector<signed char>& flip, VertexFaces& vf) {
  for (int f = 0; f < mesh.n_faces(); ++f) {
    if (flip[f] != 1) continue;
    const auto& t = mesh.faces[f];
    for (int j = 0; j < 3; ++j) {
      if ((j >= 1 && t[j] == t[0]) || (j == 2 && t[j] == t[1])) continue;  // each vertex once
      for (int k = vf.offset[t[j]]; k < vf.offset[t[j] + 1]; ++k)
        if (vf.face[k] == f && vf.corner[k] != 0) vf.corner[k] = static_cast<unsigned char>(3 - vf.corner[k]);
    }
  }
}

uint64_t position_hash(Vec3 p) {
  uint64_t h = 1469598103934665603ull;
  for (int k = 0; k < 3; ++k) {
    double x = p[k];
    if (x == 0) x = 0;  // -0 and +0 are the same position
    uint64_t bits;
    std::memcpy(&bits, &x, sizeof bits);
    h = (h ^ bits) * 1099511628211ull;
    h ^= h >> 29;
  }
  return h;
}

// The hashes of vertices that share their hash with another vertex (sorted, each once). On a mesh
// without coincident vertices this is empty, and the check costs one parallel sort of 64-bit keys.
std::vector<uint64_t> shared_position_hashes(const std::vector<uint64_t>& hash) {
  std::vector<uint64_t> sorted;
  sized(sorted, hash.size());
#pragma omp parallel for schedule(static)
  for (size_t v = 0; v < hash.size(); ++v) sorted[v] = hash[v];
  __gnu_parallel::sort(sorted.begin(), sorted.end());
  std::vector<uint64_t> shared;
  for (size_t i = 1; i < sorted.size(); ++i)
    if (sorted[i] == sorted[i - 1] && (shared.empty() || shared.back() != sorted[i])) shared.push_back(sorted[i]);
  return shared;
}

// For every vertex, the first input vertex at its exact position (itself if none; -1 if not
// finite); empty when no two vertices share a position. Vertices are told apart by a 64-bit hash
// of their exact coordinates (computed in parallel); only those whose hash another vertex shares
// are compared by their coordinates.
std::vector<int> first_at_same_position(const TriMesh& mesh, long long& welded) {
  const int nv = mesh.n_vertices();
  std::vector<uint64_t> hash;
  sized(hash, size_t(nv));
#pragma omp parallel for schedule(static)
  for (int v = 0; v < nv; ++v) hash[v] = position_hash(mesh.vertices[v]);
  const std::vector<uint64_t> shared = shared_position_hashes(hash);
  if (shared.empty()) return {};
  std::vector<int> rep_of;
  sized(rep_of, size_t(nv), -1);
  std::vector<std::pair<uint64_t, int>> keyed;  // the vertices of shared hashes, in input order per hash
  for (int v = 0; v < nv; ++v) {
    if (std::binary_search(shared.begin(), shared.end(), hash[v]))
      keyed.emplace_back(hash[v], v);
    else if (mesh.vertices[v].allFinite())
      rep_of[v] = v;
  }
  std::sort(keyed.begin(), keyed.end());
  const int nk = static_cast<int>(keyed.size());
  for (int i = 0; i < nk;) {
    int j = i;
    while (j < nk && keyed[j].first == keyed[i].first) ++j;
    for (int k = i; k < j; ++k) {  // a run of equal hashes
      const int v = keyed[k].second;
      if (!mesh.vertices[v].allFinite()) continue;
      for (int l = i; l < k; ++l) {
        const int u = keyed[l].second;
        if (rep_of[u] == u && mesh.vertices[u] == mesh.vertices[v]) {
          rep_of[v] = u;
          ++welded;
          break;
        }
      }
      if (rep_of[v] < 0) rep_of[v] = v;
    }
    i = j;
  }
  return rep_of;
}

// 1. Weld vertices at exactly the same position.
void weld_coincident_vertices(TriMesh& mesh, RepairReport& rep, std::vector<int>* of_input) {
  const int nv = mesh.n_vertices();
  const std::vector<int> rep_of = first_at_same_position(mesh, rep.welded_vertices);
  if (rep.welded_vertices == 0) return;
  std::vector<int> index(nv, -1);
  int kept = 0;
  for (int v = 0; v < nv; ++v)
    if (rep_of[v] < 0 || rep_of[v] == v) {
      index[v] = kept;
      mesh.vertices[kept++] = mesh.vertices[v];
    }
  for (int v = 0; v < nv; ++v)
    if (index[v] < 0) index[v] = index[rep_of[v]];
  mesh.vertices.resize(kept);
  for (auto& f : mesh.faces)
    for (int& v : f) v = index[v];
  if (of_input) *of_input = std::move(index);
}

int valence(const VertexFaces& vf, int v) { return vf.offset[v + 1] - vf.offset[v]; }

// Whether an earlier face has the same three vertices. It is looked for among the faces of the
// face's vertex of least valence (no global sort; linear in the faces even around a vertex of very
// high valence).
bool repeats_an_earlier_face(const TriMesh& mesh, const VertexFaces& vf, int i) {
  const auto& t = mesh.faces[i];
  int c = t[0];
  for (int v : t)
    if (valence(vf, v) < valence(vf, c)) c = v;
  auto key = t;
  std::sort(key.begin(), key.end());
  for (int k = vf.offset[c]; k < vf.offset[c + 1]; ++k) {
    const int g = vf.face[k];
    if (g >= i) continue;
    auto kg = mesh.faces[g];
    std::sort(kg.begin(), kg.end());
    if (kg == key) return true;
  }
  return false;
}

// 2. Drop faces collapsed by welding and duplicated faces (vf: the adjacency, renewed if faces go).
void drop_collapsed_and_duplicate_faces(TriMesh& mesh, VertexFaces& vf, RepairReport& rep) {
  const int nf = mesh.n_faces();
  std::vector<char> drop;
  sized(drop, size_t(nf), char(0));
  long long collapsed = 0, duplicates = 0;
  const bool welded = rep.welded_vertices > 0;
#pragma omp parallel for schedule(dynamic, 4096) reduction(+ : collapsed, duplicates)
  for (int i = 0; i < nf; ++i) {
    const auto& t = mesh.faces[i];
    if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2]) {
      if (welded) drop[i] = 1, ++collapsed;  // input degeneracies stay (counted later)
    } else if (repeats_an_earlier_face(mesh, vf, i)) {
      drop[i] = 1, ++duplicates;
    }
  }
  rep.collapsed_faces = collapsed;
  rep.duplicate_faces = duplicates;
  if (collapsed + duplicates == 0) return;
  size_t kept = 0;
  for (int i = 0; i < nf; ++i)
    if (!drop[i]) mesh.faces[kept++] = mesh.faces[i];
  mesh.faces.resize(kept);
  vf = vertex_faces(mesh);
}

// Per face and side: the neighbour across it (-1: boundary or non-manifold) and whether the two
// traverse the edge in the same direction (then one of them must be flipped).
struct FaceNeighbours {
  std::vector<std::array<int, 3>> across;
  std::vector<std::array<char, 3>> same_direction;
  std::vector<char> closed;  // every edge of the face has exactly two faces
  long long same_direction_pairs = 0;  // 0: every part is coherently oriented already
};

// The face across an edge is found among the faces of the edge's end of least valence; only a
// manifold edge (exactly two faces) gives a neighbour.
FaceNeighbours face_neighbours(const TriMesh& mesh, const VertexFaces& vf) {
  const int nf = mesh.n_faces();
  FaceNeighbours n;
  sized(n.across, size_t(nf), std::array<int, 3>{-1, -1, -1});
  sized(n.same_direction, size_t(nf), std::array<char, 3>{0, 0, 0});
  sized(n.closed, size_t(nf), char(1));
  long long same_pairs = 0;
#pragma omp parallel for schedule(dynamic, 4096) reduction(+ : same_pairs)
  for (int f = 0; f < nf; ++f) {
    const auto& t = mesh.faces[f];
    for (int j = 0; j < 3; ++j) {
      const int a = t[j], b = t[(j + 1) % 3];
      if (a == b) {
        n.closed[f] = 0;
        continue;
      }
      const int c = valence(vf, a) <= valence(vf, b) ? a : b;
      int found = -1, count = 0;
      char same = 0;
      for (int k = vf.offset[c]; k < vf.offset[c + 1]; ++k) {
        const int g = vf.face[k];
        if (g == f) continue;
        const auto& u = mesh.faces[g];
        for (int i = 0; i < 3; ++i) {
          if (u[i] == a && u[(i + 1) % 3] == b) ++count, found = g, same = 1;
          if (u[i] == b && u[(i + 1) % 3] == a) ++count, found = g, same = 0;
        }
      }
      if (count == 1) {
        n.across[f][j] = found;
        n.same_direction[f][j] = same;
        same_pairs += same;
      } else {
        n.closed[f] = 0;
      }
    }
  }
  n.same_direction_pairs = same_pairs;
  return n;
}

// Breadth-first from `seed` over manifold edges: the part's faces, each with the flip that makes it
// agree with the seed (flip[f] set). Returns false when the part cannot be oriented coherently.
bool spread_orientation(int seed, const FaceNeighbours& n, std::vector<signed char>& flip, std::vector<int>& part,
                        bool& closed) {
  flip[seed] = 0;
  part.assign(1, seed);
  bool conflict = false;
  closed = true;
  for (size_t q = 0; q < part.size(); ++q) {
    const int f = part[q];
    closed = closed && n.closed[f];
    for (int j = 0; j < 3; ++j) {
      const int g = n.across[f][j];
      if (g < 0) continue;
      const signed char want = static_cast<signed char>(flip[f] ^ (n.same_direction[f][j] ? 1 : 0));
      if (flip[g] < 0) {
        flip[g] = want;
        part.push_back(g);
      } else if (flip[g] != want) {
        conflict = true;
      }
    }
  }
  return !conflict;
}

// Six times the signed volume of the tetrahedron of face f and the origin.
double face_volume_6(const TriMesh& mesh, int f) {
  const auto& t = mesh.faces[f];
  return mesh.vertices[t[0]].dot(mesh.vertices[t[1]].cross(mesh.vertices[t[2]]));
}

double signed_volume_6(const TriMesh& mesh, const std::vector<int>& part, const std::vector<signed char>& flip) {
  double vol = 0;
  for (int f : part) vol += flip[f] ? -face_volume_6(mesh, f) : face_volume_6(mesh, f);
  return vol;
}

// Each face's part over manifold edges, as an index 0, 1, ... in the order of the parts' first
// faces (`count`: how many), found on every core.
std::vector<int> manifold_parts(const FaceNeighbours& n, int& count) {
  const int nf = static_cast<int>(n.across.size());
  DisjointSets sets(nf);
#pragma omp parallel for schedule(dynamic, 4096)
  for (int f = 0; f < nf; ++f)
    for (int g : n.across[f])
      if (g >= 0) sets.unite(f, g);
  return std::move(sets).numbered(count);
}

// Orientation when no manifold edge is traversed twice in one direction: nothing to make coherent;
// only a closed part with its normals inwards is turned (positive signed volume).
std::vector<signed char> reverse_inward_closed_parts(TriMesh& mesh, const FaceNeighbours& n, RepairReport& rep) {
  const int nf = mesh.n_faces();
  int parts = 0;
  const std::vector<int> part = manifold_parts(n, parts);
  std::vector<char> closed(size_t(parts), 1);
  std::vector<double> volume_6(size_t(parts), 0.0);
  for (int f = 0; f < nf; ++f) closed[part[f]] &= n.closed[f];
  for (int f = 0; f < nf; ++f)
    if (closed[part[f]]) volume_6[part[f]] += face_volume_6(mesh, f);
  std::vector<signed char> flip;
  sized(flip, size_t(nf), static_cast<signed char>(0));
  for (int q = 0; q < parts; ++q) rep.reversed_parts += closed[q] && volume_6[q] < 0;
  if (rep.reversed_parts == 0) return flip;
  for (int f = 0; f < nf; ++f)
    if (closed[part[f]] && volume_6[part[f]] < 0) flip[f] = 1, std::swap(mesh.faces[f][1], mesh.faces[f][2]);
  return flip;
}

// 3. Coherent orientation per part, the majority's; a closed part's normals outwards (positive
// signed volume). Returns each face's flip (1: turned).
std::vector<signed char> orient_parts(TriMesh& mesh, const FaceNeighbours& n, RepairReport& rep) {
  if (n.same_direction_pairs == 0) return reverse_inward_closed_parts(mesh, n, rep);
  const int nf = mesh.n_faces();
  std::vector<signed char> flip;
  sized(flip, size_t(nf), static_cast<signed char>(-1));
  std::vector<int> part;
  part.reserve(size_t(nf));
  advise_huge_pages(part.data(), size_t(nf) * sizeof(int));
  for (int seed = 0; seed < nf; ++seed) {
    if (flip[seed] >= 0) continue;
    bool closed = false;
    if (!spread_orientation(seed, n, flip, part, closed)) {
      ++rep.conflicting_parts;
      for (int f : part) flip[f] = 0;  // not safe to change: leave the part as it was
      continue;
    }
    long long flips = 0;
    for (int f : part) flips += flip[f];
    if (2 * flips > static_cast<long long>(part.size())) {
      for (int f : part) flip[f] ^= 1;
      flips = static_cast<long long>(part.size()) - flips;
    }
    rep.flipped_faces += flips;
    if (closed && signed_volume_6(mesh, part, flip) < 0) {
      for (int f : part) flip[f] ^= 1;
      ++rep.reversed_parts;
    }
    for (int f : part)
      if (flip[f]) std::swap(mesh.faces[f][1], mesh.faces[f][2]);
  }
  return flip;
}

}  // namespace

RepairReport repair_in_place(TriMesh& mesh, std::vector<int>* of_input, VertexFaces* faces) {
  count_work(Work::Repair);
  RepairReport rep;
  const int nv = mesh.n_vertices();
  if (of_input) {
    of_input->resize(nv);
    std::iota(of_input->begin(), of_input->end(), 0);
  }
  // A face referring to a missing vertex is not repairable here: the mesh stays as it is, for
  // require_triangles() to refuse with its message.
  for (const auto& f : mesh.faces)
    for (int v : f)
      if (v < 0 || v >= nv) return rep;
  weld_coincident_vertices(mesh, rep, of_input);
  VertexFaces vf = vertex_faces(mesh);
  drop_collapsed_and_duplicate_faces(mesh, vf, rep);
  const std::vector<signed char> flip = orient_parts(mesh, face_neighbours(mesh, vf), rep);
  if (faces) {
    if (rep.flipped_faces + rep.reversed_parts > 0) swap_flipped_corners(mesh, flip, vf);
    *faces = std::move(vf);
  }
  return rep;
}

}  // namespace reliefkit
