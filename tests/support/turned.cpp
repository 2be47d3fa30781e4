#include "turned.h"

#include "shapes.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <random>

namespace rktest {
using namespace reliefkit;

namespace {

// The globe's height along the axis over its radius across: not a sphere, whose zone would turn
// about every axis through its centre.
constexpr double kFlat = 0.75;

// The base profile at parameter t from its middle (the arc length, for the cylinder and the cone): (radius, height) and the outward normal.
struct ProfilePoint {
  Vec2 rz, normal;
};
ProfilePoint profile_at(const TurnedOptions& o, double t) {
  switch (o.shape) {
    case TurnedShape::cylinder:
      return {Vec2(o.radius, t), Vec2(1, 0)};
    case TurnedShape::cone: {
      const double a = o.cone_half_angle_deg * M_PI / 180;
      return {Vec2(o.radius + t * std::sin(a), t * std::cos(a)), Vec2(std::cos(a), -std::sin(a))};
    }
    case TurnedShape::globe: {  // an oblate belly: an ellipse's arc, radius R across, 0.75 R along the axis
      const double phi = t / o.radius;
      return {Vec2(o.radius * std::cos(phi), kFlat * o.radius * std::sin(phi)),
              Vec2(kFlat * std::cos(phi), std::sin(phi)).normalized()};
    }
  }
  return {};
}

double half_arc(const TurnedOptions& o) {
  switch (o.shape) {
    case TurnedShape::cylinder:
      return o.length / 2;
    case TurnedShape::cone:
      return o.length / 2 / std::cos(o.cone_half_angle_deg * M_PI / 180);
    case TurnedShape::globe:
      return o.radius * std::asin(std::min(1.0, o.length / 2 / (kFlat * o.radius)));
  }
  return 0;
}

// Distance from p to the segment ab.
double distance_to_segment_2d(const Vec2& p, const Vec2& a, const Vec2& b) {
  const Vec2 ab = b - a;
  const double u = std::clamp((p - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
  return (p - a - u * ab).norm();
}

// The frieze's share of full height at (along the circumference, along the profile), `h` the half
// arc: strokes of half-width w, eased over w.
double frieze(double along, double t, double h, double circumference, double w) {
  auto stroke = [&](double d) {
    const double x = std::clamp((1.5 * w - d) / w, 0.0, 1.0);
    return x * x * (3 - 2 * x);
  };
  double share = std::max(stroke(std::abs(t - 0.8 * h)), stroke(std::abs(t + 0.8 * h)));  // the border lines
  for (int k = 0; k < 4; ++k) {
    const double c = (k + 0.5) * circumference / 4;
    const Vec2 p(std::remainder(along - c, circumference), t);  // near this figure, the seam's wrap taken off
    const double body = distance_to_segment_2d(p, Vec2(0, -0.55 * h), Vec2(0, 0.25 * h));
    const double legs = std::min(distance_to_segment_2d(p, Vec2(0, -0.15 * h), Vec2(-0.12 * h, -0.6 * h)),
                                 distance_to_segment_2d(p, Vec2(0, -0.15 * h), Vec2(0.12 * h, -0.6 * h)));
    const double arm = distance_to_segment_2d(p, Vec2(0, 0.12 * h), Vec2(0.28 * h, 0.42 * h));  // raised forwards (+along)
    const double head = std::abs((p - Vec2(0, 0.42 * h)).norm() - 0.1 * h);         // a ring
    share = std::max({share, stroke(body), stroke(legs), stroke(arm), stroke(head)});
    const Vec2 star = Vec2(std::remainder(along - c - circumference / 8, circumference), t - 0.35 * h);
    for (int ray = 0; ray < 3; ++ray) {
      const double a = ray * M_PI / 3;
      const Vec2 d(0.1 * h * std::cos(a), 0.1 * h * std::sin(a));
      share = std::max(share, stroke(distance_to_segment_2d(star, -d, d)));
    }
  }
  return share;
}

// The design's height at angle theta and arc length t: five round bumps (a seal's figures), a
// band round the middle a fifth of the length wide (its edges eased over two edge lengths), or
// the frieze.
double design(const TurnedOptions& o, double theta, double t, double radius) {
  if (o.frieze) {
    const double c = 2 * M_PI * radius;
    return o.relief * frieze(radius * std::remainder(theta, 2 * M_PI) + c / 2, t, half_arc(o), c, 0.8 * o.edge);
  }
  if (o.band) {
    const double half = 0.1 * 2 * half_arc(o), ease = 2 * o.edge;
    const double inside = std::clamp((half - std::abs(t)) / ease + 0.5, 0.0, 1.0);
    return o.relief * inside * inside * (3 - 2 * inside);
  }
  const double sigma = 0.08 * half_arc(o) * 2;
  double h = 0;
  for (int k = 0; k < 5; ++k) {
    const double bump_theta = -2.5 + 1.2 * k, bump_t = (k % 2 ? 0.3 : -0.25) * half_arc(o);
    const double along = radius * std::remainder(theta - bump_theta, 2 * M_PI), across = t - bump_t;
    h = std::max(h, std::exp(-(along * along + across * across) / (2 * sigma * sigma)));
  }
  return o.relief * h;
}

// A grid of rings between vertex rings `outer` and `inner` (columns each), faces facing `up`
// (+z) or down.
void join_rings(const std::vector<int>& outer, const std::vector<int>& inner, bool up, reliefkit::TriMesh& mesh) {
  const size_t n = outer.size();
  for (size_t j = 0; j < n; ++j) {
    const int a = outer[j], b = outer[(j + 1) % n], c = inner[j], d = inner[(j + 1) % n];
    if (up) mesh.faces.push_back({a, b, d}), mesh.faces.push_back({a, d, c});
    else mesh.faces.push_back({a, d, b}), mesh.faces.push_back({a, c, d});
  }
}

// The ends of a closed seal (flat annuli from the wall's end rows in to the bore) and its bore (a
// tube facing the axis), joined to the wall.
void close_ends(const TurnedOptions& o, int rows, int columns, Turned& out) {
  const double half = o.length / 2, dtheta = 2 * M_PI / columns;
  auto ring = [&](double radius, double z) {
    std::vector<int> r;
    for (int j = 0; j < columns; ++j) {
      r.push_back(out.mesh.n_vertices());
      out.mesh.vertices.emplace_back(radius * std::cos(j * dtheta), radius * std::sin(j * dtheta), z);
      out.relief.push_back(std::nan(""));
    }
    return r;
  };
  const int steps = std::max(1, int(std::lround((o.radius - o.bore_radius) / o.edge)));
  std::vector<int> inner_end[2];
  for (int end = 0; end < 2; ++end) {
    const int row = end == 0 ? 0 : rows - 1;
    const double z = end == 0 ? -half : half;
    std::vector<int> previous(static_cast<size_t>(columns));
    for (int j = 0; j < columns; ++j) previous[size_t(j)] = row * columns + j;
    for (int k = 1; k <= steps; ++k) {
      const std::vector<int> next = ring(o.radius - k * (o.radius - o.bore_radius) / steps, z);
      join_rings(previous, next, end == 1, out.mesh);
      previous = next;
    }
    inner_end[end] = previous;
  }
  const int bore_rows = std::max(1, int(std::lround(o.length / o.edge)));
  std::vector<int> previous = inner_end[0];
  for (int i = 1; i <= bore_rows; ++i) {
    const std::vector<int> next = i == bore_rows ? inner_end[1] : ring(o.bore_radius, -half + i * o.length / bore_rows);
    for (int j = 0; j < columns; ++j) {  // facing the axis: the wall's winding reversed
      const int a = previous[size_t(j)], b = previous[size_t((j + 1) % columns)], c = next[size_t(j)], d = next[size_t((j + 1) % columns)];
      out.mesh.faces.push_back({a, d, b}), out.mesh.faces.push_back({a, c, d});
    }
    previous = next;
  }
}

}  // namespace

Turned make_turned(const TurnedOptions& o) {
  Turned out;
  std::mt19937 rng(o.seed);
  std::uniform_real_distribution<double> jitter(-0.3, 0.3);
  const double half = half_arc(o);
  double widest = 0;
  for (int k = 0; k <= 20; ++k) widest = std::max(widest, profile_at(o, -half + k * half / 10).rz.x());
  const int columns = std::max(8, int(std::lround(2 * M_PI * widest / o.edge)));
  const int rows = std::max(2, int(std::lround(2 * half / o.edge)) + 1);
  const double dt = 2 * half / (rows - 1), dtheta = 2 * M_PI / columns;
  for (int i = 0; i < rows; ++i)
    for (int j = 0; j < columns; ++j) {
      const bool edge_row = i == 0 || i == rows - 1;
      const double t = -half + (i + (o.irregular && !edge_row ? jitter(rng) : 0)) * dt;
      const double theta = (j + (o.irregular ? jitter(rng) : 0)) * dtheta;
      const ProfilePoint p = profile_at(o, t);
      const double w = design(o, theta, t, p.rz.x());
      const Vec2 rz = p.rz + w * p.normal;
      out.mesh.vertices.emplace_back(rz.x() * std::cos(theta), rz.x() * std::sin(theta), rz.y());
      out.relief.push_back(w);
    }
  for (int i = 0; i + 1 < rows; ++i)
    for (int j = 0; j < columns; ++j) {
      const int a = i * columns + j, b = i * columns + (j + 1) % columns, c = a + columns, d = b + columns;
      out.mesh.faces.push_back({a, b, d});
      out.mesh.faces.push_back({a, d, c});
    }
  out.wall_faces = out.mesh.n_faces();
  if (o.closed && o.shape == TurnedShape::cylinder) close_ends(o, rows, columns, out);
  out.middle_radius = profile_at(o, 0).rz.x();
  if (o.random_pose) {
    std::normal_distribution<double> gauss;
    place_randomly(out.mesh, out.axis_point, out.axis_direction, rng, gauss, 50);
  }
  return out;
}

}  // namespace rktest
