#include "shapes.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <array>
#include <limits>
#include <map>

namespace rktest {

double Rng::uniform() {
  s ^= s << 13;
  s ^= s >> 7;
  s ^= s << 17;
  return (s >> 11) * (1.0 / 9007199254740992.0);
}
double Rng::normal() {
  double u1 = std::max(uniform(), 1e-300), u2 = uniform();
  return std::sqrt(-2 * std::log(u1)) * std::cos(2 * M_PI * u2);
}

double median(std::vector<double> v) { return percentile(std::move(v), 0.5); }
double percentile(std::vector<double> v, double q) {
  if (v.empty()) return 0;
  size_t k = std::min(v.size() - 1, size_t(q * (v.size() - 1) + 0.5));
  std::nth_element(v.begin(), v.begin() + k, v.end());
  return v[k];
}

// Periodic/regular grid triangulation with alternating diagonals.
static void grid_faces(TriMesh& m, int nu, int nv, bool wrap_u, bool wrap_v) {
  int cu = wrap_u ? nu : nu - 1, cv = wrap_v ? nv : nv - 1;
  auto id = [&](int i, int j) { return (i % nu) * nv + (j % nv); };
  for (int i = 0; i < cu; ++i)
    for (int j = 0; j < cv; ++j) {
      int a = id(i, j), b = id(i + 1, j), c = id(i + 1, j + 1), d = id(i, j + 1);
      if ((i + j) % 2 == 0) {
        m.faces.push_back({a, b, c});
        m.faces.push_back({a, c, d});
      } else {
        m.faces.push_back({a, b, d});
        m.faces.push_back({b, c, d});
      }
    }
}

TriMesh torus(double R, double r, int nu, int nv, double jitter, uint32_t seed) {
  TriMesh m;
  Rng rng(seed);
  for (int i = 0; i < nu; ++i)
    for (int j = 0; j < nv; ++j) {
      double u = (i + jitter * (rng.uniform() - 0.5)) * 2 * M_PI / nu;
      double v = (j + jitter * (rng.uniform() - 0.5)) * 2 * M_PI / nv;
      m.vertices.emplace_back((R + r * std::cos(v)) * std::cos(u), (R + r * std::cos(v)) * std::sin(u),
                              r * std::sin(v));
    }
  grid_faces(m, nu, nv, true, true);
  return m;
}

void torus_params(double R, double r, const Vec3& p, double& u, double& v) {
  u = std::atan2(p.y(), p.x());
  double rho = std::hypot(p.x(), p.y()) - R;
  v = std::atan2(p.z(), rho);
  (void)r;
}

TriMesh sphere(double r, int levels, double jitter, uint32_t seed) {
  const double t = (1 + std::sqrt(5.0)) / 2;
  TriMesh m;
  m.vertices = {{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0}, {0, -1, t}, {0, 1, t},
                {0, -1, -t}, {0, 1, -t}, {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}};
  m.faces = {{0, 11, 5}, {0, 5, 1}, {0, 1, 7}, {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
             {11, 10, 2}, {10, 7, 6}, {7, 1, 8}, {3, 9, 4}, {3, 4, 2}, {3, 2, 6}, {3, 6, 8},
             {3, 8, 9}, {4, 9, 5}, {2, 4, 11}, {6, 2, 10}, {8, 6, 7}, {9, 8, 1}};
  for (auto& p : m.vertices) p.normalize();
  for (int l = 0; l < levels; ++l) {
    std::map<std::pair<int, int>, int> mid;
    auto midpoint = [&](int a, int b) {
      auto key = std::minmax(a, b);
      auto it = mid.find(key);
      if (it != mid.end()) return it->second;
      m.vertices.push_back((m.vertices[a] + m.vertices[b]).normalized());
      return mid[key] = int(m.vertices.size()) - 1;
    };
    std::vector<std::array<int, 3>> nf;
    for (auto f : m.faces) {
      int a = midpoint(f[0], f[1]), b = midpoint(f[1], f[2]), c = midpoint(f[2], f[0]);
      nf.push_back({f[0], a, c});
      nf.push_back({f[1], b, a});
      nf.push_back({f[2], c, b});
      nf.push_back({a, b, c});
    }
    m.faces.swap(nf);
  }
  if (jitter > 0) {
    double h = (m.vertices[m.faces[0][0]] - m.vertices[m.faces[0][1]]).norm();
    Rng rng(seed);
    for (auto& p : m.vertices) {
      Vec3 d(rng.uniform() - 0.5, rng.uniform() - 0.5, rng.uniform() - 0.5);
      p = (p + jitter * h * (d - p * p.dot(d))).normalized();
    }
  }
  for (auto& p : m.vertices) p *= r;
  return m;
}

TriMesh cylinder(double r, double h, int nu, int nz, double jitter, uint32_t seed) {
  TriMesh m;
  Rng rng(seed);
  for (int i = 0; i < nu; ++i)
    for (int j = 0; j <= nz; ++j) {
      double ju = jitter * (rng.uniform() - 0.5), jz = jitter * (rng.uniform() - 0.5);
      if (j == 0 || j == nz) jz = 0;
      double u = (i + ju) * 2 * M_PI / nu, z = (j + jz) * h / nz - h / 2;
      m.vertices.emplace_back(r * std::cos(u), r * std::sin(u), z);
    }
  // grid over (u, z) with u wrapping; orientation: (u, z) increasing gives outward normal.
  grid_faces(m, nu, nz + 1, true, false);
  return m;
}

TriMesh height_field(const std::function<double(double, double)>& f, double half, int n, double jitter,
                     uint32_t seed, int* origin_index) {
  TriMesh m;
  Rng rng(seed);
  double hstep = 2 * half / n;
  for (int i = 0; i <= n; ++i)
    for (int j = 0; j <= n; ++j) {
      double x = -half + i * hstep, y = -half + j * hstep;
      bool border = i == 0 || j == 0 || i == n || j == n;
      bool origin = (2 * i == n && 2 * j == n);
      if (jitter > 0 && !border && !origin) {
        x += jitter * hstep * (rng.uniform() - 0.5);
        y += jitter * hstep * (rng.uniform() - 0.5);
      }
      if (origin && origin_index) *origin_index = int(m.vertices.size());
      m.vertices.emplace_back(x, y, f(x, y));
    }
  grid_faces(m, n + 1, n + 1, false, false);
  return m;
}

TriMesh relief_torus(long faces) {
  int nv = std::max(8, int(std::sqrt(faces / 2.0 / 3.0)));
  int nu = std::max(8, int(faces / 2 / nv));
  TriMesh m = torus(3, 1, nu, nv, 0.4, 11);
  for (auto& p : m.vertices) {
    double u = std::atan2(p.y(), p.x());
    Vec3 c(3 * std::cos(u), 3 * std::sin(u), 0);
    Vec3 d = p - c;
    double v = std::atan2(d.z(), std::hypot(p.x(), p.y()) - 3);
    p = c + d * (1 + 0.05 * std::sin(12 * u) * std::sin(6 * v));
  }
  return m;
}

namespace {
// Closest point of triangle abc to p (Ericson, Real-Time Collision Detection, 5.1.5).
Vec3 closest_on_triangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return a;
  const Vec3 bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return b;
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return a + d1 / (d1 - d3) * ab;
  const Vec3 cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return c;
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return a + d2 / (d2 - d6) * ac;
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) return b + (d4 - d3) / ((d4 - d3) + (d5 - d6)) * (c - b);
  const double denom = 1.0 / (va + vb + vc);
  return a + ab * (vb * denom) + ac * (vc * denom);
}
}  // namespace

std::vector<double> distance_to_surface(const TriMesh& mesh, const std::vector<Vec3>& points, double reach) {
  double cell = reach;
  for (const auto& f : mesh.faces)
    for (int j = 0; j < 3; ++j)
      cell = std::max(cell, (mesh.vertices[f[j]] - mesh.vertices[f[(j + 1) % 3]]).norm());
  Vec3 lo = mesh.vertices[0];
  for (const auto& p : mesh.vertices) lo = lo.cwiseMin(p);
  auto key = [&](const Vec3& p) {
    const Eigen::Array3d q = ((p - lo) / cell).array().floor();
    return std::array<long, 3>{long(q[0]), long(q[1]), long(q[2])};
  };
  std::map<std::array<long, 3>, std::vector<int>> grid;  // faces by the cell of their first corner
  for (int f = 0; f < mesh.n_faces(); ++f) grid[key(mesh.vertices[mesh.faces[f][0]])].push_back(f);
  std::vector<double> out;
  for (const Vec3& p : points) {
    const auto k = key(p);
    double best = std::numeric_limits<double>::infinity();
    // A face within `reach` <= cell of p has its first corner within two cells of p's.
    for (long dx = -2; dx <= 2; ++dx)
      for (long dy = -2; dy <= 2; ++dy)
        for (long dz = -2; dz <= 2; ++dz) {
          auto it = grid.find({k[0] + dx, k[1] + dy, k[2] + dz});
          if (it == grid.end()) continue;
          for (int f : it->second) {
            const auto& t = mesh.faces[f];
            const Vec3 q = closest_on_triangle(p, mesh.vertices[t[0]], mesh.vertices[t[1]], mesh.vertices[t[2]]);
            best = std::min(best, (p - q).norm());
          }
        }
    out.push_back(best <= reach ? best : std::numeric_limits<double>::infinity());
  }
  return out;
}

Vec3 gauss_vec3(std::normal_distribution<double>& gauss, std::mt19937& rng) {
  const double z = gauss(rng), y = gauss(rng), x = gauss(rng);
  return {x, y, z};
}

void place_randomly(TriMesh& mesh, Vec3& axis_point, Vec3& axis_direction, std::mt19937& rng,
                    std::normal_distribution<double>& gauss, double spread) {
  const Vec3 axis = gauss_vec3(gauss, rng);
  Eigen::Quaterniond q(gauss(rng), axis.x(), axis.y(), axis.z());
  q.normalize();
  const Vec3 shift = spread * gauss_vec3(gauss, rng);
  for (Vec3& p : mesh.vertices) p = q * p + shift;
  axis_point = q * axis_point + shift, axis_direction = q * axis_direction;
}

}  // namespace rktest
