// The synthetic finds of finds.h.
#include "finds.h"

#include <algorithm>
#include <cmath>

#include "shapes.h"

namespace rktest {
using reliefkit::Mat3;
using reliefkit::Vec2;
using reliefkit::Vec3;

namespace {

// The radius along the unit direction d at which (|x|/a)^m + (|y|/b)^m + (|z|/c)^mz = 1: a rounded
// box whose +z face is flatter (larger mz) than its -z face.
double rounded_box_radius(const Vec3& d, const Vec3& half, double m, double mz_front, double mz_back) {
  const double mz = d.z() > 0 ? mz_front : mz_back;
  auto level = [&](double r) {
    return std::pow(std::abs(r * d.x()) / half.x(), m) + std::pow(std::abs(r * d.y()) / half.y(), m) + std::pow(std::abs(r * d.z()) / half.z(), mz);
  };
  double lo = 0, hi = half.norm();
  for (int k = 0; k < 50; ++k) (level(0.5 * (lo + hi)) < 1 ? lo : hi) = 0.5 * (lo + hi);
  return 0.5 * (lo + hi);
}

// A wedge's impression at (x, y) relative to its head's centre, pointing its tail to +x: a
// triangular pyramid pit (the stylus's corner) and a tapering groove behind it; 0..1.
double wedge(const Vec2& p, double size) {
  const Vec2 corners[3] = {Vec2(-0.6, 0.8), Vec2(-0.6, -0.8), Vec2(0.5, 0)};
  double inside = 1e9;
  for (int k = 0; k < 3; ++k) {
    const Vec2 a = corners[k] * size, b = corners[(k + 1) % 3] * size, e = (b - a).normalized();
    const Vec2 n(-e.y(), e.x());  // pointing in
    inside = std::min(inside, (p - a).dot(n));
  }
  const double head = std::max(0.0, inside / (0.35 * size));
  const double t = (p.x() - 0.3 * size) / (2.2 * size);
  const double tail = t > 0 && t < 1 ? 0.6 * (1 - t) * std::max(0.0, 1 - std::abs(p.y()) / (0.25 * size)) : 0;
  return std::min(1.0, std::max(head, tail));
}

// Lines of wedges across a face `half` wide and high (its frame's x, y), within its flat part.
double wedges_on_face(const Vec2& p, const Vec2& half, int lines) {
  const double size = 2.4, pitch_x = 6.5, pitch_y = 2 * half.y() * 0.8 / lines;
  double depth = 0;
  for (int line = 0; line < lines; ++line) {
    const double y = half.y() * 0.8 - pitch_y * (line + 0.5);
    for (double x = -half.x() * 0.75 + 0.6 * size * (line % 2); x < half.x() * 0.7; x += pitch_x)
      depth = std::max(depth, wedge(p - Vec2(x, y), size));
  }
  return depth;
}

Find turned(reliefkit::TriMesh mesh, const Mat3& turn, double width, double height, double thickness) {
  for (Vec3& p : mesh.vertices) p = turn * p;
  Find f;
  f.mesh = std::move(mesh), f.front = turn * Vec3::UnitZ(), f.up = turn * Vec3::UnitY();
  f.width = width, f.height = height, f.thickness_at_middle = thickness;
  return f;
}
}  // namespace

Find tablet(const TabletOptions& o, const Mat3& turn) {
  reliefkit::TriMesh m = sphere(1, o.levels);
  const Vec3 half(o.width / 2, o.height / 2, o.thickness / 2);
  for (Vec3& p : m.vertices) {
    const Vec3 d = p;
    p = d * rounded_box_radius(d, half, 6, 6, 2.5);
    const double facing = std::abs(d.z()) / d.norm();
    const double flat = std::clamp((facing - 0.35) / 0.25, 0.0, 1.0);  // wedges only on the faces, eased off at the rim
    const double pressed = flat * o.wedge_depth * wedges_on_face(Vec2(d.z() > 0 ? p.x() : -p.x(), p.y()), Vec2(half.x(), half.y()), d.z() > 0 ? 8 : 5);
    p.z() -= d.z() > 0 ? pressed : -pressed;
  }
  const double back = rounded_box_radius(Vec3(0, 0, -1), half, 6, 6, 2.5), front = rounded_box_radius(Vec3(0, 0, 1), half, 6, 6, 2.5);
  return turned(std::move(m), turn, o.width, o.height, front + back);
}

Find blade(const BladeOptions& o, const Mat3& turn) {
  reliefkit::TriMesh m = sphere(1, o.levels);
  // Flake scars: dishes struck from both edges (centres just beyond them, staggered along the
  // blade); the dorsal face is the lowest of them and of the central ridge, so that neighbouring
  // scars meet in sharp arrises, as on a knapped face.
  std::vector<Vec2> scars;
  for (double y : {-0.38, -0.19, 0.0, 0.19, 0.38}) scars.emplace_back(-1.15, y);
  for (double y : {-0.28, -0.09, 0.1, 0.29}) scars.emplace_back(1.15, y);
  const double curvature = 1.1 * o.dorsal / std::pow(0.5 * o.width * 1.15, 2);
  auto dorsal_height = [&](const Vec2& at, double half_width) {
    double z = o.dorsal * (1 - 0.55 * std::abs(at.x()) / half_width);  // the central ridge
    for (const Vec2& c : scars) z = std::min(z, curvature * (at - Vec2(c.x() * half_width, c.y() * o.length)).squaredNorm());
    return z;
  };
  for (Vec3& p : m.vertices) {
    const double sy = p.y(), rise = std::sqrt(std::abs(p.z()));  // 0 at the edge, 1 in the middle
    const double half_width = 0.5 * o.width * (1 - 0.45 * std::pow(std::max(0.0, sy), 2));
    const Vec2 at(half_width * p.x(), 0.5 * o.length * sy);
    const double bulb = 1.8 * std::exp(-(at - Vec2(0, -0.38 * o.length)).squaredNorm() / 49);
    const double z = p.z() > 0 ? rise * dorsal_height(at, half_width) : -rise * (o.ventral + bulb);
    p = Vec3(at.x(), at.y(), z);
  }
  return turned(std::move(m), turn, o.width, o.length, dorsal_height(Vec2(0, 0), 0.5 * o.width) + o.ventral);
}

Find coin(const CoinOptions& o, const Mat3& turn) {
  reliefkit::TriMesh m = sphere(1, o.levels);
  const double radius = 0.5 * o.diameter, half = 0.5 * o.thickness;
  auto eased = [](double inside, double width) { return std::clamp(inside / width, 0.0, 1.0); };
  auto star = [&](const Vec2& p) {  // five points, the top one up; inside: > 0
    const double angle = std::atan2(p.x(), p.y()), r = p.norm(), sector = 2 * M_PI / 5;
    const double off = std::abs(std::remainder(angle, sector)) / (sector / 2);  // 0 at a point, 1 between two
    return (0.62 * radius) * (1 - 0.55 * off) - r;
  };
  for (Vec3& p : m.vertices) {
    const Vec3 d = p;
    const double rise = std::pow(std::abs(d.z()), 0.25);  // a flat face, a rounded edge
    const Vec2 at = radius * Vec2(d.x(), d.y()) / std::max(1e-12, std::hypot(d.x(), d.y())) * std::min(1.0, std::hypot(d.x(), d.y()) / 0.97);
    const double r = at.norm(), rim = eased(0.6 - std::abs(r - 0.9 * radius), 0.3);
    double design;
    if (d.z() > 0) {
      design = eased(star(at), 0.4);
    } else {
      const Vec2 seen(-at.x(), at.y());  // as the reverse is seen, turned about the vertical axis
      const double ring = eased(0.9 - std::abs(r - 0.5 * radius), 0.3), bar = eased(1.0 - std::abs(seen.y()), 0.3) * eased(0.5 * radius - std::abs(seen.x()), 0.3);
      design = std::max(ring, bar);
    }
    const double z = half * rise + o.relief * std::max(rim, design) * std::clamp((std::abs(d.z()) - 0.3) / 0.2, 0.0, 1.0);
    p = Vec3(at.x(), at.y(), d.z() > 0 ? z : -z);
  }
  return turned(std::move(m), turn, o.diameter, o.diameter, o.thickness);
}

}  // namespace rktest
