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

// The design's height at angle theta and arc length t: five round bumps (a seal's figures), or a
// band round the middle a fifth of the length wide, its edges eased over two edge lengths.
double design(const TurnedOptions& o, double theta, double t, double radius) {
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
  out.middle_radius = profile_at(o, 0).rz.x();
  if (o.random_pose) {
    std::normal_distribution<double> gauss;
    place_randomly(out.mesh, out.axis_point, out.axis_direction, rng, gauss, 50);
  }
  return out;
}

}  // namespace rktest
