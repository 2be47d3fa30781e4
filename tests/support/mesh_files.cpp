#include "mesh_files.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <unordered_map>

namespace rktest {
namespace {

struct Prop {
  std::string name, type, count_type;  // count_type non-empty for lists
};

size_t type_size(const std::string& t) {
  if (t == "char" || t == "uchar" || t == "int8" || t == "uint8") return 1;
  if (t == "short" || t == "ushort" || t == "int16" || t == "uint16") return 2;
  if (t == "int" || t == "uint" || t == "float" || t == "int32" || t == "uint32" || t == "float32") return 4;
  if (t == "double" || t == "float64") return 8;
  throw std::runtime_error("PLY: unknown type " + t);
}

double read_binary(std::istream& in, const std::string& t) {
  unsigned char b[8];
  size_t n = type_size(t);
  in.read(reinterpret_cast<char*>(b), n);
  if (!in) throw std::runtime_error("PLY: truncated file");
  if (t == "char" || t == "int8") return int8_t(b[0]);
  if (t == "uchar" || t == "uint8") return b[0];
  if (t == "short" || t == "int16") { int16_t v; std::memcpy(&v, b, 2); return v; }
  if (t == "ushort" || t == "uint16") { uint16_t v; std::memcpy(&v, b, 2); return v; }
  if (t == "int" || t == "int32") { int32_t v; std::memcpy(&v, b, 4); return v; }
  if (t == "uint" || t == "uint32") { uint32_t v; std::memcpy(&v, b, 4); return v; }
  if (t == "float" || t == "float32") { float v; std::memcpy(&v, b, 4); return v; }
  double v; std::memcpy(&v, b, 8); return v;
}

MeshFile read_ply(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error("cannot open " + path);
  std::string line, format;
  struct Element { std::string name; long long count; std::vector<Prop> props; };
  std::vector<Element> elems;
  while (std::getline(in, line)) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    std::istringstream ss(line);
    std::string kw;
    ss >> kw;
    if (kw == "format") ss >> format;
    else if (kw == "element") { Element e; ss >> e.name >> e.count; elems.push_back(e); }
    else if (kw == "property") {
      Prop p; std::string t; ss >> t;
      if (t == "list") { ss >> p.count_type >> p.type >> p.name; } else { p.type = t; ss >> p.name; }
      elems.back().props.push_back(p);
    } else if (kw == "end_header") break;
  }
  bool ascii = format == "ascii";
  if (!ascii && format != "binary_little_endian") throw std::runtime_error("PLY: unsupported format " + format);
  MeshFile mf;
  for (const auto& e : elems) {
    for (long long i = 0; i < e.count; ++i) {
      std::vector<double> scalars;
      std::vector<std::vector<double>> lists;
      std::istringstream ls;
      if (ascii) { std::getline(in, line); ls.str(line); }
      for (const auto& p : e.props) {
        if (!p.count_type.empty()) {
          double n; if (ascii) ls >> n; else n = read_binary(in, p.count_type);
          std::vector<double> l(static_cast<size_t>(n));
          for (auto& x : l) { if (ascii) ls >> x; else x = read_binary(in, p.type); }
          lists.push_back(l);
          scalars.push_back(0);
        } else {
          double x; if (ascii) { std::string tok; ls >> tok; x = std::stod(tok); } else x = read_binary(in, p.type);
          scalars.push_back(x);
        }
      }
      if (e.name == "vertex") {
        reliefkit::Vec3 p(0, 0, 0);
        for (size_t k = 0; k < e.props.size(); ++k) {
          const auto& n = e.props[k].name;
          if (n == "x") p.x() = scalars[k]; else if (n == "y") p.y() = scalars[k]; else if (n == "z") p.z() = scalars[k];
          else if (e.props[k].count_type.empty()) mf.vertex_props[n].push_back(scalars[k]);
        }
        mf.mesh.vertices.push_back(p);
      } else if (e.name == "face" && !lists.empty()) {
        const auto& l = lists[0];
        for (size_t k = 2; k < l.size(); ++k) mf.mesh.faces.push_back({int(l[0]), int(l[k - 1]), int(l[k])});
      } else if (e.name == "edge" && scalars.size() >= 2) {
        mf.edges.push_back({int(scalars[0]), int(scalars[1])});
      }
    }
  }
  return mf;
}

MeshFile read_obj(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot open " + path);
  MeshFile mf;
  std::string line;
  auto idx = [](const std::string& tok) { return std::stoi(tok.substr(0, tok.find('/'))) - 1; };
  while (std::getline(in, line)) {
    std::istringstream ss(line);
    std::string kw;
    ss >> kw;
    if (kw == "v") { double x, y, z; ss >> x >> y >> z; mf.mesh.vertices.emplace_back(x, y, z); }
    else if (kw == "f") {
      std::vector<int> ids; std::string tok;
      while (ss >> tok) ids.push_back(idx(tok));
      for (size_t k = 2; k < ids.size(); ++k) mf.mesh.faces.push_back({ids[0], ids[k - 1], ids[k]});
    } else if (kw == "l") {
      std::vector<int> ids; std::string tok;
      while (ss >> tok) ids.push_back(idx(tok));
      for (size_t k = 1; k < ids.size(); ++k) mf.edges.push_back({ids[k - 1], ids[k]});
    }
  }
  return mf;
}

}  // namespace

MeshFile read_mesh(const std::string& path) {
  std::string ext = path.size() > 4 ? path.substr(path.size() - 4) : "";
  for (auto& c : ext) c = char(std::tolower(c));
  return ext == ".obj" ? read_obj(path) : read_ply(path);
}

reliefkit::Polylines polylines_of(const MeshFile& f) {
  reliefkit::Polylines p;
  p.points = f.mesh.vertices;
  p.strength.assign(p.points.size(), 1);
  p.segments = f.edges;
  return p;
}

void write_ply(const std::string& path, const reliefkit::TriMesh& m) {
  std::ofstream out(path, std::ios::binary);
  out << "ply\nformat binary_little_endian 1.0\nelement vertex " << m.vertices.size()
      << "\nproperty float x\nproperty float y\nproperty float z\nelement face " << m.faces.size()
      << "\nproperty list uchar int vertex_indices\nend_header\n";
  for (const auto& p : m.vertices) {
    float v[3] = {float(p.x()), float(p.y()), float(p.z())};
    out.write(reinterpret_cast<const char*>(v), sizeof v);
  }
  for (const auto& f : m.faces) {
    unsigned char n = 3;
    out.write(reinterpret_cast<const char*>(&n), 1);
    int32_t ids[3] = {f[0], f[1], f[2]};
    out.write(reinterpret_cast<const char*>(ids), sizeof ids);
  }
  if (!out) throw std::runtime_error("cannot write " + path);
}

// Share of the length of `a` within `tol` of a segment of `b` (a uniform grid over b).
double near_share(const MeshFile& a, const MeshFile& b, double tol) {
  using reliefkit::Vec3;
  auto key = [tol](const Vec3& p) {
    return std::array<long, 3>{long(std::floor(p.x() / tol)), long(std::floor(p.y() / tol)), long(std::floor(p.z() / tol))};
  };
  struct Hash {
    size_t operator()(const std::array<long, 3>& k) const { return size_t(k[0] * 73856093 ^ k[1] * 19349663 ^ k[2] * 83492791); }
  };
  std::unordered_map<std::array<long, 3>, std::vector<int>, Hash> grid;
  const auto& bv = b.mesh.vertices;
  for (size_t s = 0; s < b.edges.size(); ++s) {
    const Vec3 &p = bv[b.edges[s][0]], &q = bv[b.edges[s][1]];
    const int steps = 1 + int((p - q).norm() / tol);
    for (int k = 0; k <= steps; ++k) {
      auto c = key(p + (q - p) * (double(k) / steps));
      auto& cell = grid[c];
      if (cell.empty() || cell.back() != int(s)) cell.push_back(int(s));
    }
  }
  auto dist = [&](const Vec3& x, int s) {
    const Vec3 &p = bv[b.edges[s][0]], &q = bv[b.edges[s][1]];
    const Vec3 d = q - p;
    const double t = d.squaredNorm() > 0 ? std::clamp((x - p).dot(d) / d.squaredNorm(), 0.0, 1.0) : 0.0;
    return (x - (p + t * d)).norm();
  };
  double near = 0, total = 0;
  for (const auto& e : a.edges) {
    const Vec3 &p = a.mesh.vertices[e[0]], &q = a.mesh.vertices[e[1]];
    const Vec3 mid = 0.5 * (p + q);
    const double len = (p - q).norm();
    total += len;
    auto c = key(mid);
    bool ok = false;
    for (long dx = -1; dx <= 1 && !ok; ++dx)
      for (long dy = -1; dy <= 1 && !ok; ++dy)
        for (long dz = -1; dz <= 1 && !ok; ++dz) {
          auto it = grid.find({c[0] + dx, c[1] + dy, c[2] + dz});
          if (it == grid.end()) continue;
          for (int s : it->second)
            if (dist(mid, s) <= tol) {
              ok = true;
              break;
            }
        }
    if (ok) near += len;
  }
  return total > 0 ? near / total : 1.0;
}


}  // namespace rktest
