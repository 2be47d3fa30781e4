// ReliefKit — the base models (thesis sect. 7.5): a model moved to its principal frame, the
// parametric classes of the shipped library (surfaces of revolution with nozzles, spouts and
// handles) and a model's silhouette features. See base_library.h.
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <random>

#include "reliefkit/drawing/base_library.h"

namespace reliefkit {

TriMesh normalize_to_principal_axes(const TriMesh& mesh) {
  // Area-weighted moments of the surface (each face's area at its centroid and vertices).
  double area = 0;
  Vec3 c = Vec3::Zero();
  std::vector<double> face_area(mesh.faces.size(), 0);
  for (size_t f = 0; f < mesh.faces.size(); ++f) {
    const auto& t = mesh.faces[f];
    const Vec3 &a = mesh.vertices[t[0]], &b = mesh.vertices[t[1]], &d = mesh.vertices[t[2]];
    const double ar = 0.5 * (b - a).cross(d - a).norm();
    if (!std::isfinite(ar)) continue;
    face_area[f] = ar;
    area += ar;
    c += ar * (a + b + d) / 3;
  }
  if (!(area > 0)) throw InputError("The model has no surface (all its faces are degenerate).");
  c /= area;
  Mat3 cov = Mat3::Zero();
  for (size_t f = 0; f < mesh.faces.size(); ++f) {
    if (face_area[f] == 0) continue;
    const auto& t = mesh.faces[f];
    const Vec3 a = mesh.vertices[t[0]] - c, b = mesh.vertices[t[1]] - c, d = mesh.vertices[t[2]] - c;
    // Second moment of a triangle: A/12 (sum p p^T + (sum p)(sum p)^T).
    const Vec3 s = a + b + d;
    cov += face_area[f] / 12 * (a * a.transpose() + b * b.transpose() + d * d.transpose() + s * s.transpose());
  }
  Eigen::SelfAdjointEigenSolver<Mat3> eig(cov);
  Mat3 axes;
  for (int k = 0; k < 3; ++k) axes.col(k) = eig.eigenvectors().col(2 - k);  // decreasing extent
  // Signs: the third moment along each axis positive (a deterministic choice; retrieval tries all).
  for (int k = 0; k < 2; ++k) {
    double m3 = 0;
    for (const auto& p : mesh.vertices)
      if (p.allFinite()) m3 += std::pow((p - c).dot(axes.col(k)), 3);
    if (m3 < 0) axes.col(k) = -axes.col(k);
  }
  axes.col(2) = axes.col(0).cross(axes.col(1));
  TriMesh out = mesh;
  double radius = 0;
  for (auto& p : out.vertices) {
    p = axes.transpose() * (p - c);
    if (p.allFinite()) radius = std::max(radius, p.norm());
  }
  if (radius > 0)
    for (auto& p : out.vertices) p /= radius;
  return out;
}

namespace {
const char* const kClassNames[kBaseClasses] = {"lamp", "bowl", "cup", "krater", "jug", "amphora", "plate", "cylinder", "sphere"};

// A profile (r, z) from the bottom pole to the top pole through knots (z, r) joined by Catmull-Rom
// curves, with flat discs closing the bottom and the top.
std::vector<Vec2> revolution_profile(const std::vector<Vec2>& knots_zr, bool discs = true) {
  std::vector<Vec2> rz;
  const size_t n = knots_zr.size();
  auto at = [&](long i) { return knots_zr[size_t(std::clamp(i, 0L, long(n) - 1))]; };
  if (discs && knots_zr.front().y() > 0)
    for (int k = 0; k < 4; ++k) rz.push_back(Vec2(knots_zr.front().y() * k / 4.0, knots_zr.front().x()));
  for (size_t i = 0; i + 1 < n; ++i) {
    const Vec2 p0 = at(long(i) - 1), p1 = at(long(i)), p2 = at(long(i) + 1), p3 = at(long(i) + 2);
    for (int s = 0; s < 24; ++s) {
      const double t = s / 24.0, t2 = t * t, t3 = t2 * t;
      const Vec2 q = 0.5 * ((2 * p1) + (-p0 + p2) * t + (2 * p0 - 5 * p1 + 4 * p2 - p3) * t2 + (-p0 + 3 * p1 - 3 * p2 + p3) * t3);
      rz.push_back(Vec2(std::max(q.y(), 0.0), q.x()));
    }
  }
  rz.push_back(Vec2(knots_zr.back().y(), knots_zr.back().x()));
  if (discs && knots_zr.back().y() > 0)
    for (int k = 3; k >= 0; --k) rz.push_back(Vec2(knots_zr.back().y() * k / 4.0, knots_zr.back().x()));
  return rz;
}

// Resamples a polyline to `m` points evenly spaced by arc length.
std::vector<Vec2> resample(const std::vector<Vec2>& pts, int m) {
  std::vector<double> s(pts.size(), 0);
  for (size_t i = 1; i < pts.size(); ++i) s[i] = s[i - 1] + (pts[i] - pts[i - 1]).norm();
  std::vector<Vec2> out;
  size_t j = 0;
  for (int k = 0; k < m; ++k) {
    const double t = s.back() * k / (m - 1);
    while (j + 2 < pts.size() && s[j + 1] < t) ++j;
    const double len = s[j + 1] - s[j];
    const double a = len > 0 ? std::clamp((t - s[j]) / len, 0.0, 1.0) : 0;
    out.push_back(pts[j] + a * (pts[j + 1] - pts[j]));
  }
  return out;
}

struct Bump {  // radial bump toward angle `angle`: length, angular width, height centre and half-height
  double angle, length, width, z, half_height;
};

void append(TriMesh& m, const TriMesh& part) {
  const int off = m.n_vertices();
  m.vertices.insert(m.vertices.end(), part.vertices.begin(), part.vertices.end());
  for (auto f : part.faces) m.faces.push_back({f[0] + off, f[1] + off, f[2] + off});
}

TriMesh revolve(const std::vector<Vec2>& profile_rz, int around, const std::vector<Bump>& bumps) {
  double len = 0;
  for (size_t i = 1; i < profile_rz.size(); ++i) len += (profile_rz[i] - profile_rz[i - 1]).norm();
  double rmax = 0;
  for (const auto& p : profile_rz) rmax = std::max(rmax, p.x());
  const int rings = std::max(8, int(std::lround(len / (2 * M_PI * rmax / around))) + 1);
  const auto pr = resample(profile_rz, rings);
  TriMesh m;
  m.vertices.push_back(Vec3(0, 0, pr.front().y()));
  for (int j = 1; j + 1 < rings; ++j)
    for (int i = 0; i < around; ++i) {
      const double t = 2 * M_PI * i / around;
      double r = pr[size_t(j)].x();
      for (const auto& b : bumps) {
        double d = std::remainder(t - b.angle, 2 * M_PI);
        const double dz = (pr[size_t(j)].y() - b.z) / b.half_height;
        r += b.length * std::exp(-(d / b.width) * (d / b.width)) * std::exp(-dz * dz * dz * dz);
      }
      m.vertices.push_back(Vec3(r * std::cos(t), r * std::sin(t), pr[size_t(j)].y()));
    }
  const int top = m.n_vertices();
  m.vertices.push_back(Vec3(0, 0, pr.back().y()));
  auto id = [&](int j, int i) { return 1 + (j - 1) * around + (i % around); };
  for (int i = 0; i < around; ++i) m.faces.push_back({0, id(1, i + 1), id(1, i)});
  for (int j = 1; j + 2 < rings; ++j)
    for (int i = 0; i < around; ++i) {
      m.faces.push_back({id(j, i), id(j, i + 1), id(j + 1, i + 1)});
      m.faces.push_back({id(j, i), id(j + 1, i + 1), id(j + 1, i)});
    }
  for (int i = 0; i < around; ++i) m.faces.push_back({top, id(rings - 2, i), id(rings - 2, i + 1)});
  return m;
}

// A tube of radius `radius` along the cubic Bezier p0..p3; `up` is a direction not along it.
TriMesh tube(const Vec3& p0, const Vec3& p1, const Vec3& p2, const Vec3& p3, double radius, const Vec3& up) {
  constexpr int kAlong = 28, kAround = 12;
  TriMesh m;
  for (int s = 0; s <= kAlong; ++s) {
    const double t = double(s) / kAlong, u = 1 - t;
    const Vec3 p = u * u * u * p0 + 3 * u * u * t * p1 + 3 * u * t * t * p2 + t * t * t * p3;
    const Vec3 d = (3 * u * u * (p1 - p0) + 6 * u * t * (p2 - p1) + 3 * t * t * (p3 - p2)).normalized();
    const Vec3 n = up.cross(d).normalized(), b = d.cross(n);
    for (int k = 0; k < kAround; ++k) {
      const double a = 2 * M_PI * k / kAround;
      m.vertices.push_back(p + radius * (std::cos(a) * n + std::sin(a) * b));
    }
  }
  for (int s = 0; s < kAlong; ++s)
    for (int k = 0; k < kAround; ++k) {
      const int a = s * kAround + k, b = s * kAround + (k + 1) % kAround, c = a + kAround, d = b + kAround;
      m.faces.push_back({a, b, d});
      m.faces.push_back({a, d, c});
    }
  // Outward: the first face's normal must point away from the path.
  const auto& f = m.faces[0];
  const Vec3 nrm = (m.vertices[f[1]] - m.vertices[f[0]]).cross(m.vertices[f[2]] - m.vertices[f[0]]);
  if (nrm.dot(m.vertices[f[0]] - p0) < 0)
    for (auto& g : m.faces) std::swap(g[1], g[2]);
  return m;
}

// Radius of the profile at height z (the outermost crossing).
double radius_at(const std::vector<Vec2>& rz, double z) {
  double best = 0;
  for (size_t i = 1; i < rz.size(); ++i) {
    const Vec2 a = rz[i - 1], b = rz[i];
    if ((a.y() - z) * (b.y() - z) > 0 || a.y() == b.y()) continue;
    const double t = (z - a.y()) / (b.y() - a.y());
    best = std::max(best, a.x() + t * (b.x() - a.x()));
  }
  return best;
}

// A loop handle in the xz-plane on the side `side` (+1: +x, -1: -x) from height z0 to z1 bulging out by `out`.
TriMesh side_handle(const std::vector<Vec2>& rz, int side, double z0, double z1, double out, double thick) {
  const double r0 = radius_at(rz, z0) - thick, r1 = radius_at(rz, z1) - thick;
  const double rr = std::max(r0, r1) + out;
  return tube(Vec3(side * r0, 0, z0), Vec3(side * (rr + 0.3 * out), 0, z0 + 0.1 * (z1 - z0)),
              Vec3(side * (rr + 0.3 * out), 0, z1 - 0.05 * (z1 - z0)), Vec3(side * r1, 0, z1), thick, Vec3(0, 1, 0));
}
// A horizontal loop handle at height z on the side `side`, spanning +-half_angle around the body.
TriMesh horizontal_handle(const std::vector<Vec2>& rz, int side, double z, double half_angle, double out, double thick) {
  const double r = radius_at(rz, z) - thick;
  const double c = std::cos(half_angle), s = std::sin(half_angle);
  const double x = side * r * c, y = r * s, xo = side * (r * c + out);
  return tube(Vec3(x, -y, z), Vec3(xo, -0.8 * y, z + 0.4 * out), Vec3(xo, 0.8 * y, z + 0.4 * out), Vec3(x, y, z), thick,
              Vec3(0, 0, 1));
}

// What a class's model is made of: a profile (knots (z, r) joined by revolution_profile, or the
// profile `rz` itself), radial bumps (nozzle, spout, knob) and separate parts (handles).
struct ModelParts {
  std::vector<Vec2> knots, rz;
  std::vector<Bump> bumps;
  TriMesh extra;
};
// A uniform random draw in [a, b) from the model's generator.
using Uniform = std::function<double(double, double)>;

// Lamp: low lens-shaped body, a nozzle towards +x; ring handle, knob or none at -x.
void lamp_parts(ModelParts& m, const Uniform& U, int variant) {
  const double h = U(0.32, 0.5), rb = U(0.45, 0.6), rt = U(0.6, 0.72);
  m.knots = {{0, rb}, {0.15 * h, rb + 0.1}, {0.45 * h, 1.0}, {0.8 * h, U(0.82, 0.9)}, {h, rt}};
  m.rz = revolution_profile(m.knots);
  m.bumps.push_back({0, U(0.45, 0.95), U(0.22, 0.4), 0.5 * h, 0.4 * h});
  if (variant % 3 == 1) append(m.extra, side_handle(m.rz, -1, 0.35 * h, h, U(0.25, 0.4), 0.06));
  if (variant % 3 == 2) m.bumps.push_back({M_PI, U(0.18, 0.3), 0.18, 0.6 * h, 0.3 * h});
}

// Bowl.
void bowl_parts(ModelParts& m, const Uniform& U, int) {
  const double h = U(0.4, 0.65), e = U(1.7, 2.6), rf = U(0.3, 0.45);
  for (int k = 0; k <= 8; ++k) {
    const double z = h * k / 8;
    m.knots.push_back({z, std::max(rf, std::pow(1 - std::pow(1 - z / h, e), 1 / e))});
  }
}

// Cup: tapering beaker with one handle.
void cup_parts(ModelParts& m, const Uniform& U, int) {
  const double rr = U(0.33, 0.45), rb = rr * U(0.55, 0.75), rm = rr * U(0.95, 1.1);
  m.knots = {{0, rb}, {0.08, rb * 1.05}, {0.4, rm}, {0.85, rr * 0.97}, {1, rr}};
  m.rz = revolution_profile(m.knots);
  // Drawn last argument first (C++ leaves the order of a call's arguments open: GCC made the
  // library that way, clang would draw another cup).
  const double out = U(0.2, 0.3), z1 = U(0.75, 0.85), z0 = U(0.2, 0.3);
  append(m.extra, side_handle(m.rz, -1, z0, z1, out, 0.035));
}

// Krater: bell on a stemmed foot, two horizontal handles.
void krater_parts(ModelParts& m, const Uniform& U, int) {
  const double R = U(0.5, 0.7);
  m.knots = {{0, 0.3 * R}, {0.05, 0.28 * R}, {0.12, 0.12 * R}, {0.2, 0.2 * R}, {0.45, 0.75 * R}, {0.8, 0.95 * R}, {1.0, R}};
  m.rz = revolution_profile(m.knots);
  const double z = U(0.4, 0.55);
  append(m.extra, horizontal_handle(m.rz, 1, z, 0.45, U(0.12, 0.2), 0.035));
  append(m.extra, horizontal_handle(m.rz, -1, z, 0.45, U(0.12, 0.2), 0.035));
}

// Jug: bulging body, narrow neck, handle at -x; spout at +x for odd variants.
void jug_parts(ModelParts& m, const Uniform& U, int variant) {
  const double rb = U(0.3, 0.4), rn = rb * U(0.35, 0.5);
  m.knots = {{0, 0.6 * rb}, {0.1, 0.85 * rb}, {0.35, rb}, {0.6, 0.85 * rb}, {0.75, rn}, {0.88, rn}, {1, rn * 1.25}};
  m.rz = revolution_profile(m.knots);
  const double out = U(0.15, 0.25), z0 = U(0.5, 0.6);  // last argument first, as for the cup
  append(m.extra, side_handle(m.rz, -1, z0, 0.93, out, 0.035));
  if (variant % 2 == 1) m.bumps.push_back({0, U(0.12, 0.22), 0.35, 1.0, 0.08});
}

// Amphora: tall, pointed toe, two handles from shoulder to neck.
void amphora_parts(ModelParts& m, const Uniform& U, int) {
  const double rb = U(0.2, 0.27), rn = rb * U(0.35, 0.45);
  m.knots = {{0, 0.05 * rb}, {0.05, 0.15 * rb}, {0.2, 0.75 * rb}, {0.5, rb}, {0.68, 0.85 * rb}, {0.76, rn}, {0.95, rn}, {1, rn * 1.3}};
  m.rz = revolution_profile(m.knots);
  const double out = U(0.1, 0.16);
  append(m.extra, side_handle(m.rz, 1, 0.7, 0.92, out, 0.03));
  append(m.extra, side_handle(m.rz, -1, 0.7, 0.92, out, 0.03));
}

// Plate.
void plate_parts(ModelParts& m, const Uniform& U, int) {
  const double h = U(0.1, 0.2), rf = U(0.3, 0.5);
  m.knots = {{0, rf}, {0.25 * h, rf * 1.05}, {0.6 * h, U(0.7, 0.8)}, {h, 1.0}};
}

// Cylinder.
void cylinder_parts(ModelParts& m, const Uniform& U, int) {
  const double r = U(0.15, 1.0);
  m.knots = {{0, r}, {1, r}};
}

// Sphere (slightly oblate or prolate).
void sphere_parts(ModelParts& m, const Uniform& U, int) {
  const double c = U(0.85, 1.15);
  for (int k = 0; k <= 16; ++k) {
    const double a = M_PI * k / 16;
    m.rz.push_back(Vec2(std::sin(a), c * (1 - std::cos(a))));
  }
  for (auto& p : m.rz) p.x() = std::max(p.x(), 0.0);
}
}  // namespace

const char* base_class_name(int c) { return c >= 0 && c < kBaseClasses ? kClassNames[c] : "model"; }

std::vector<BaseModelSpec> standard_base_specs(int per_class, unsigned seed) {
  std::vector<BaseModelSpec> specs;
  for (int c = 0; c < kBaseClasses; ++c)
    for (int v = 0; v < per_class; ++v) {
      BaseModelSpec s;
      s.kind = c;
      s.variant = v;
      s.seed = seed * 1000003u + unsigned(c) * 7919u + unsigned(v) * 104729u;
      char name[64];
      std::snprintf(name, sizeof name, "%s_%02d", kClassNames[c], v + 1);
      s.name = name;
      specs.push_back(s);
    }
  return specs;
}

TriMesh make_base_model(const BaseModelSpec& spec, int around) {
  using Parts = void (*)(ModelParts&, const Uniform&, int);
  static const Parts kParts[kBaseClasses] = {lamp_parts, bowl_parts,     cup_parts,      krater_parts, jug_parts,
                                             amphora_parts, plate_parts, cylinder_parts, sphere_parts};
  std::mt19937 rng(spec.seed);
  const Uniform U = [&](double a, double b) { return std::uniform_real_distribution<double>(a, b)(rng); };
  ModelParts m;
  kParts[spec.kind >= 0 && spec.kind < kBaseClasses ? spec.kind : kBaseClasses - 1](m, U, spec.variant);
  if (m.rz.empty()) m.rz = revolution_profile(m.knots);
  TriMesh model = revolve(m.rz, std::max(around, 16), m.bumps);
  append(model, m.extra);
  return model;
}

std::array<SilhouetteFeature, 3> model_features(const TriMesh& normalized) {
  return {circle_feature(mesh_outline(normalized, 2, 3)), circle_feature(mesh_outline(normalized, 1, 3)),
          circle_feature(mesh_outline(normalized, 1, 2))};
}

}  // namespace reliefkit
