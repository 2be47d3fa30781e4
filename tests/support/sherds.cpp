#include "sherds.h"

#include "shapes.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <random>

namespace rktest {

using reliefkit::TriMesh;
using reliefkit::Vec2;
using reliefkit::Vec3;

namespace {

constexpr double kSherdWall = 5;  // mm
// Breaks: their points off the smooth break by this much (mm, each coordinate; a sherd's break is
// jagged at the scale of its grains and flakes, about a tenth of the wall's thickness).
constexpr double kBreakRoughness = 0.12 * kSherdWall;

// The outer wall's section (radius, height), mm: from the base's middle on the axis (leaving it
// square, as a flat base does) to the rim.
std::vector<Vec2> control_points(VesselShape shape) {
  switch (shape) {
    case VesselShape::jar:
      return {{0, 0}, {20, 0}, {32, 4}, {45, 25}, {50, 50}, {44, 80}, {30, 100}, {27, 108}, {31, 118}};
    case VesselShape::bowl:
      return {{0, 0}, {15, 0}, {30, 6}, {42, 18}, {50, 34}, {54, 48}};
    case VesselShape::beaker:
      return {{0, 0}, {18, 0}, {22, 3}, {24, 30}, {27, 60}, {32, 90}, {36, 110}};
  }
  return {};
}

// A Catmull-Rom spline through the points, sampled every `step` mm of its length (the first
// phantom point mirrors the second about the axis, so the curve leaves the axis square to it).
std::vector<Vec2> spline(const std::vector<Vec2>& c, double step) {
  std::vector<Vec2> p{Vec2(-c[1].x(), c[1].y())};
  p.insert(p.end(), c.begin(), c.end());
  p.push_back(2 * c.back() - c[c.size() - 2]);
  std::vector<Vec2> dense;
  for (size_t i = 1; i + 2 < p.size(); ++i)
    for (int k = 0; k < 200; ++k) {
      const double t = k / 200.0, t2 = t * t, t3 = t2 * t;
      dense.push_back(0.5 * (2 * p[i] + (p[i + 1] - p[i - 1]) * t + (2 * p[i - 1] - 5 * p[i] + 4 * p[i + 1] - p[i + 2]) * t2 +
                             (3 * p[i] - p[i - 1] - 3 * p[i + 1] + p[i + 2]) * t3));
    }
  dense.push_back(c.back());
  std::vector<Vec2> out{dense.front()};
  double run = 0;
  for (size_t k = 1; k < dense.size(); ++k) {
    run += (dense[k] - dense[k - 1]).norm();
    if (run >= step) out.push_back(dense[k]), run = 0;
  }
  if ((out.back() - dense.back()).norm() > 0.3 * step) out.push_back(dense.back());
  else out.back() = dense.back();
  return out;
}

// Outward unit normals of a polyline in (radius, height).
std::vector<Vec2> normals_of(const std::vector<Vec2>& line) {
  std::vector<Vec2> n(line.size());
  for (size_t k = 0; k < line.size(); ++k) {
    const Vec2 t = (line[std::min(k + 1, line.size() - 1)] - line[k > 0 ? k - 1 : 0]).normalized();
    n[k] = Vec2(t.y(), -t.x());
  }
  return n;
}

struct Builder {
  TriMesh mesh;
  Vec3 middle = Vec3::Zero();  // for orienting the break faces outwards
  int add(const Vec3& p) {
    mesh.vertices.push_back(p);
    return mesh.n_vertices() - 1;
  }
  void face(int a, int b, int c) { mesh.faces.push_back({a, b, c}); }
  // A face of a break down the side at the start (side -1) or the end (+1) of the piece's span,
  // turned to face out of the piece (along -/+ the direction round the axis).
  void break_face(int a, int b, int c, int side) {
    const Vec3 &p = mesh.vertices[size_t(a)], &q = mesh.vertices[size_t(b)], &r = mesh.vertices[size_t(c)];
    const Vec3 centre = (p + q + r) / 3;
    const Vec3 around = Vec3(-centre.y(), centre.x(), 0);
    if ((q - p).cross(r - p).dot(side * around) < 0) std::swap(b, c);
    face(a, b, c);
  }
};

}  // namespace

Sherd make_sherd(const SherdOptions& o) {
  std::mt19937 rng(o.seed);
  std::normal_distribution<double> gauss(0, 1);
  std::uniform_real_distribution<double> uniform(0, 1);
  Sherd sh;
  sh.thickness = kSherdWall;
  const std::vector<Vec2> full = spline(control_points(o.shape), o.edge);
  for (const Vec2& p : full) sh.largest_radius = std::max(sh.largest_radius, p.x());
  // The kept part of the profile, by length; a base kept starts half an edge off the axis (the
  // middle is closed by fans to the axis).
  sh.has_base = o.from <= 0, sh.has_rim = o.to >= 1;
  const size_t first = std::max<size_t>(sh.has_base ? 1 : 0, size_t(o.from * double(full.size() - 1)));
  const size_t last = std::min(full.size() - 1, size_t(std::ceil(o.to * double(full.size() - 1))));
  std::vector<Vec2> outer(full.begin() + long(first), full.begin() + long(last) + 1);
  if (sh.has_base) outer.front() = Vec2(0.5 * o.edge, 0);
  const std::vector<Vec2> normal = normals_of(outer);
  std::vector<Vec2> inner(outer.size());
  for (size_t k = 0; k < outer.size(); ++k) inner[k] = outer[k] - kSherdWall * normal[k];
  sh.outer = outer, sh.inner = inner;
  if (sh.has_base) sh.outer.insert(sh.outer.begin(), Vec2(0, 0)), sh.inner.insert(sh.inner.begin(), Vec2(0, kSherdWall));
  sh.rim_diameter = 0;  // set with the rim's points below: where its highest point is (a rim chart's circle)
  // The section as one loop: outer wall up, the top (a rounded rim or a break), inner wall down,
  // the bottom (a break; with the base, the axis closes it).
  std::vector<Vec2> loop(outer);
  std::vector<char> rough(outer.size(), 0);
  const Vec2 tangent(-normal.back().y(), normal.back().x()), top_middle = outer.back() - 0.5 * kSherdWall * normal.back();
  const int cap = std::max(3, int(M_PI * kSherdWall / 2 / o.edge));
  for (int j = 1; j < cap; ++j) {
    const double phi = M_PI * j / cap;
    loop.push_back(sh.has_rim ? Vec2(top_middle + 0.5 * kSherdWall * (std::cos(phi) * normal.back() + std::sin(phi) * tangent))
                              : Vec2(outer.back() - kSherdWall * (double(j) / cap) * normal.back()));
    rough.push_back(!sh.has_rim);
  }
  if (sh.has_rim) {  // the cap's crest: where its circle's radius points straight up
    const double crest = std::clamp(std::atan2(tangent.y(), normal.back().y()), 0.0, M_PI);
    sh.rim_diameter = 2 * (top_middle + 0.5 * kSherdWall * (std::cos(crest) * normal.back() + std::sin(crest) * tangent)).x();
  }
  for (size_t k = inner.size(); k-- > 0;) loop.push_back(inner[k]), rough.push_back(0);
  if (!sh.has_base)
    for (int j = 1; j < cap; ++j) loop.push_back(inner.front() + kSherdWall * (double(j) / cap) * normal.front()), rough.push_back(1);
  const double span = o.span_deg * M_PI / 180, theta0 = uniform(rng) * 2 * M_PI;
  const bool whole = o.span_deg >= 360;
  const int columns = std::max(3, int(span * sh.largest_radius / o.edge));
  auto at = [&](double theta, const Vec2& rz, double depth) {
    const double r = (rz.x() - depth) * (1 + o.out_of_round * std::cos(2 * theta));
    return Vec3(r * std::cos(theta), r * std::sin(theta), rz.y());
  };
  const double groove_from = 0.5 * double(outer.size()), groove_to = 0.7 * double(outer.size());
  auto groove = [&](double theta, size_t k) {  // vertical incisions every 20 degrees
    if (!o.incised || k >= outer.size() || k < groove_from || k > groove_to) return 0.0;
    const double along = std::remainder(theta, 20 * M_PI / 180) * outer[k].x() / o.edge;
    return 1.5 * o.edge * std::exp(-along * along);
  };
  Builder b;
  const int n_columns = whole ? columns : columns + 1;
  std::vector<std::vector<int>> grid(static_cast<size_t>(n_columns), std::vector<int>(loop.size()));
  std::vector<double> theta_of(static_cast<size_t>(n_columns));
  for (int i = 0; i < n_columns; ++i) {
    double theta = theta0 + span * i / columns;
    if (o.irregular && i > 0 && i < columns) theta += (uniform(rng) - 0.5) * 0.8 * span / columns;
    theta_of[size_t(i)] = theta;
    for (size_t k = 0; k < loop.size(); ++k) {
      Vec2 rz = loop[k];
      if (o.irregular && k > 0 && k + 1 < outer.size()) rz = outer[k] + (uniform(rng) - 0.5) * 0.8 * (outer[k + 1] - outer[k]);
      Vec3 p = at(theta, rz, groove(theta, k));
      if (rough[k]) p += kBreakRoughness * rktest::gauss_vec3(gauss, rng);
      grid[size_t(i)][k] = b.add(p);
    }
  }
  const size_t n = loop.size();
  const bool closed_loop = !sh.has_base;
  for (int i = 0; i < columns; ++i) {
    const auto &c0 = grid[size_t(i)], &c1 = grid[size_t((i + 1) % n_columns)];
    for (size_t k = 0; k + 1 < n + (closed_loop ? 1 : 0); ++k) {
      const size_t k1 = (k + 1) % n;
      b.face(c0[k], c1[k], c1[k1]), b.face(c0[k], c1[k1], c0[k1]);
    }
  }
  if (sh.has_base) {  // fans to the axis: under the base and on its floor
    const int pole_out = b.add(Vec3(0, 0, 0)), pole_in = b.add(Vec3(0, 0, kSherdWall));
    for (int i = 0; i < columns; ++i) {
      const auto &c0 = grid[size_t(i)], &c1 = grid[size_t((i + 1) % n_columns)];
      b.face(pole_out, c1[0], c0[0]);
      b.face(pole_in, c0[n - 1], c1[n - 1]);
    }
    if (!whole)
      for (int i : {0, columns}) {
        const int side = i == 0 ? -1 : 1;
        b.break_face(pole_out, grid[size_t(i)][0], pole_in, side);
        b.break_face(pole_in, grid[size_t(i)][0], grid[size_t(i)][n - 1], side);
      }
  }
  if (!whole)  // the breaks down the sides: strips across the wall with a rough middle
    for (int i : {0, columns}) {
      const int side = i == 0 ? -1 : 1;
      const auto& column = grid[size_t(i)];
      const size_t O = outer.size(), I = inner.size(), top = size_t(cap - 1);
      auto inner_at = [&](size_t k) { return column[O + top + (I - 1 - k)]; };
      std::vector<int> middle(O);
      for (size_t k = 0; k < O; ++k) {
        const Vec3 p = (b.mesh.vertices[size_t(column[k])] + b.mesh.vertices[size_t(inner_at(k))]) / 2;
        middle[k] = b.add(p + kBreakRoughness * rktest::gauss_vec3(gauss, rng));
      }
      for (size_t k = 0; k + 1 < O; ++k) {
        b.break_face(column[k], column[k + 1], middle[k + 1], side), b.break_face(column[k], middle[k + 1], middle[k], side);
        b.break_face(middle[k], middle[k + 1], inner_at(k + 1), side), b.break_face(middle[k], inner_at(k + 1), inner_at(k), side);
      }
      for (size_t j = 0; j < size_t(cap); ++j)  // the top (rim or break): a fan to the middle's end
        b.break_face(middle.back(), column[O - 1 + j], column[O + j], side);
      if (!sh.has_base)  // the bottom break
        for (size_t j = 0; j < size_t(cap); ++j) b.break_face(middle.front(), column[n - size_t(cap) + j], column[(n - size_t(cap) + j + 1) % n], side);
    }
  for (Vec3& p : b.mesh.vertices) p += o.noise * o.edge * rktest::gauss_vec3(gauss, rng);
  sh.mesh = std::move(b.mesh);
  sh.axis_point = Vec3::Zero(), sh.axis_direction = Vec3::UnitZ();
  if (o.random_pose) place_randomly(sh.mesh, sh.axis_point, sh.axis_direction, rng, gauss, 100);
  return sh;
}

namespace {
double distance_to_line(const Vec2& q, const std::vector<Vec2>& line) {
  double best = INFINITY;
  for (size_t k = 0; k + 1 < line.size(); ++k) {
    const Vec2 a = line[k], ab = line[k + 1] - a;
    const double t = std::clamp((q - a).dot(ab) / std::max(ab.squaredNorm(), 1e-300), 0.0, 1.0);
    best = std::min(best, (q - a - t * ab).norm());
  }
  return best;
}
}  // namespace

SherdScore score_record(const Sherd& sh, const reliefkit::VesselRecord& r) {
  SherdScore s;
  const Vec3 d = r.axis.direction.normalized();
  s.angle_deg = std::acos(std::min(1.0, std::abs(d.dot(sh.axis_direction)))) * 180 / M_PI;
  s.up_right = d.dot(sh.axis_direction) > 0;
  Vec3 centre = Vec3::Zero();
  for (const Vec3& p : sh.mesh.vertices) centre += p / double(sh.mesh.vertices.size());
  auto foot = [&](const Vec3& a, const Vec3& dir) { return Vec3(a + (centre - a).dot(dir) * dir); };
  s.offset = (foot(r.axis.point, d) - foot(sh.axis_point, sh.axis_direction)).norm() / sh.largest_radius;
  double lowest = INFINITY;  // the record's heights start at the piece's lowest vertex
  for (const Vec3& p : sh.mesh.vertices) lowest = std::min(lowest, (p - sh.axis_point).dot(sh.axis_direction));
  std::vector<double> error;
  long right_side = 0;
  for (const auto& c : r.profile) {
    if (c.part != reliefkit::ProfilePart::outer_wall && c.part != reliefkit::ProfilePart::inner_wall) continue;
    for (const Vec2& q : c.points) {
      const Vec2 t(q.x(), q.y() + lowest);
      const double outer = distance_to_line(t, sh.outer), inner = distance_to_line(t, sh.inner);
      error.push_back(std::min(outer, inner) / sh.largest_radius);
      right_side += (c.part == reliefkit::ProfilePart::outer_wall) == (outer < inner);
    }
  }
  s.sides_right = error.empty() ? 0 : double(right_side) / double(error.size());
  s.profile_points = long(error.size());
  if (!error.empty()) {
    std::sort(error.begin(), error.end());
    s.profile_median = error[error.size() / 2], s.profile_p90 = error[size_t(0.9 * double(error.size() - 1))];
  } else {
    s.profile_median = s.profile_p90 = INFINITY;
  }
  if (sh.has_rim && r.has_rim) s.rim_diameter = std::abs(r.rim_diameter - sh.rim_diameter) / sh.rim_diameter;
  return s;
}

}  // namespace rktest
