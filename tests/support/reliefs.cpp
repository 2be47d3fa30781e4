#include "reliefs.h"

#include <algorithm>
#include <cmath>
#include <tuple>

#include "shapes.h"

namespace rktest {
namespace {

using reliefkit::Vec3;

double step(double d, double w) { return 0.5 * (1 + std::tanh(d / w)); }

void finish(Relief& r, const ReliefShape& s) {
  r.mean_edge = reliefkit::edge_length_stats(r.mesh).mean;
  if (s.noise > 0) {
    Rng rng(s.seed * 7919 + 13);
    for (size_t i = 0; i < r.mesh.vertices.size(); ++i)
      r.mesh.vertices[i] += r.base_normal[i] * (s.noise * r.mean_edge * rng.normal());
  }
}

// Distance from p to segment ab.
double seg_dist(const Vec3& p, const Vec3& a, const Vec3& b) {
  Vec3 ab = b - a;
  double l2 = ab.squaredNorm();
  double t = l2 > 0 ? std::clamp((p - a).dot(ab) / l2, 0.0, 1.0) : 0.0;
  return (p - (a + t * ab)).norm();
}

// Displaces the cylinder's vertices along its normal by height(arc length, z); records the
// base normals.
template <class Height>
void emboss_cylinder(Relief& r, double R, const Height& height) {
  for (auto& p : r.mesh.vertices) {
    double u = std::atan2(p.y(), p.x());
    Vec3 n(std::cos(u), std::sin(u), 0);
    r.base_normal.push_back(n);
    p += n * height(u * R, p.z());
  }
}

// Displaces the unit sphere's vertices along their normal by height(angle from +z); records the
// base normals.
template <class Height>
void emboss_sphere(Relief& r, const Height& height) {
  for (auto& p : r.mesh.vertices) {
    Vec3 n = p.normalized();
    r.base_normal.push_back(n);
    p = n * (1 + height(std::acos(std::clamp(n.z(), -1.0, 1.0))));
  }
}

// The true step line at angular radius a0 on the unit sphere (mid-height of the step), 4000 samples.
void sample_circle_on_sphere(Relief& r, double a0, double height) {
  for (int k = 0; k < 4000; ++k) {
    double a = 2 * M_PI * k / 4000;
    Vec3 n(std::sin(a0) * std::cos(a), std::sin(a0) * std::sin(a), std::cos(a0));
    r.boundary.push_back(n * (1 + 0.5 * height));
  }
}

}  // namespace

Relief disc_on_plane(const ReliefShape& s, int n) {
  const double R0 = 0.5;
  Relief r;
  r.mesh = height_field([&](double x, double y) { return s.height * step(R0 - std::hypot(x, y), s.width); }, 1.0, n,
                        s.jitter, s.seed);
  r.base_normal.assign(r.mesh.vertices.size(), Vec3(0, 0, 1));
  for (int k = 0; k < 4000; ++k) {
    double a = 2 * M_PI * k / 4000;
    r.boundary.emplace_back(R0 * std::cos(a), R0 * std::sin(a), 0.5 * s.height);
  }
  finish(r, s);
  return r;
}

Relief disc_on_sphere(const ReliefShape& s, int levels) {
  const double a0 = 0.5;
  Relief r;
  r.mesh = sphere(1.0, levels, s.jitter, s.seed);
  emboss_sphere(r, [&](double ang) { return s.height * step(a0 - ang, s.width); });
  sample_circle_on_sphere(r, a0, s.height);
  finish(r, s);
  return r;
}

Relief ring_on_sphere(const ReliefShape& s, int levels) {
  const double a_in = 0.3, a_out = 0.6;  // angular radii of the ring's inner and outer edges
  Relief r;
  r.mesh = sphere(1.0, levels, s.jitter, s.seed);
  emboss_sphere(r, [&](double ang) { return s.height * step(a_out - ang, s.width) * step(ang - a_in, s.width); });
  for (double a0 : {a_in, a_out}) sample_circle_on_sphere(r, a0, s.height);
  finish(r, s);
  return r;
}

Relief outlines_on_plane(const ReliefShape& s, bool with_star, bool with_rectangle, int n) {
  const Vec3 star_centre(-0.45, 0, 0), rect_centre(0.55, 0, 0);
  // The star: a ten-sided polygon, points at radius 0.38, notches at 0.19.
  std::vector<Vec3> star;
  for (int k = 0; k < 10; ++k) {
    const double a = M_PI / 2 + M_PI * k / 5, rad = k % 2 ? 0.19 : 0.38;
    star.push_back(star_centre + Vec3(rad * std::cos(a), rad * std::sin(a), 0));
  }
  // Signed distances, positive inside: to the star's sides (inside by the crossing count) and to
  // the rectangle (a box 0.15 x 0.35 grown by 0.1).
  auto inside_star = [&](double x, double y) {
    const Vec3 p(x, y, 0);
    double d = 1e9;
    bool in = false;
    for (size_t k = 0; k < star.size(); ++k) {
      const Vec3 &a = star[k], &b = star[(k + 1) % star.size()];
      d = std::min(d, seg_dist(p, a, b));
      if ((a.y() > y) != (b.y() > y) && x < a.x() + (y - a.y()) / (b.y() - a.y()) * (b.x() - a.x())) in = !in;
    }
    return in ? d : -d;
  };
  auto inside_rect = [&](double x, double y) {
    const double qx = std::abs(x - rect_centre.x()) - 0.15, qy = std::abs(y - rect_centre.y()) - 0.35;
    const double outside = std::hypot(std::max(qx, 0.0), std::max(qy, 0.0)) + std::min(std::max(qx, qy), 0.0);
    return 0.1 - outside;
  };
  Relief r;
  r.mesh = height_field([&](double x, double y) {
    return s.height * std::max(with_star ? step(inside_star(x, y), s.width) : 0.0,
                               with_rectangle ? step(inside_rect(x, y), s.width) : 0.0);
  }, 1.0, n, s.jitter, s.seed);
  r.base_normal.assign(r.mesh.vertices.size(), Vec3(0, 0, 1));
  for (size_t k = 0; with_star && k < star.size(); ++k)
    for (int i = 0; i < 400; ++i) r.boundary.push_back(star[k] + (star[(k + 1) % star.size()] - star[k]) * (i / 400.0) +
                                                       Vec3(0, 0, 0.5 * s.height));
  // The rectangle's outline: the point in each of 4000 directions from its centre (bisection).
  for (int k = 0; with_rectangle && k < 4000; ++k) {
    const double a = 2 * M_PI * k / 4000;
    const Vec3 d(std::cos(a), std::sin(a), 0);
    double lo = 0, hi = 1;
    for (int it = 0; it < 50; ++it) {
      const double mid = 0.5 * (lo + hi);
      (inside_rect(rect_centre.x() + mid * d.x(), rect_centre.y() + mid * d.y()) > 0 ? lo : hi) = mid;
    }
    r.boundary.emplace_back(rect_centre.x() + lo * d.x(), rect_centre.y() + lo * d.y(), 0.5 * s.height);
  }
  finish(r, s);
  return r;
}

Relief discs_on_cylinder(const ReliefShape& s, int nu, int nz) {
  const double R = 1, R1 = 0.4, R2 = 0.3;
  Relief r;
  r.mesh = cylinder(R, 2, nu, nz, s.jitter, s.seed);
  auto height = [&](double arc, double z) {
    double d1 = std::hypot(arc, z), d2 = std::hypot(std::remainder(arc - M_PI * R, 2 * M_PI * R), z);
    return s.height * step(R1 - d1, s.width) - s.height * step(R2 - d2, s.width);
  };
  emboss_cylinder(r, R, height);
  for (int k = 0; k < 4000; ++k) {
    double a = 2 * M_PI * k / 4000;
    for (auto [rad, center, sign] : {std::tuple{R1, 0.0, 1.0}, std::tuple{R2, M_PI * R, -1.0}}) {
      double arc = center + rad * std::cos(a), z = rad * std::sin(a), u = arc / R;
      r.boundary.push_back(Vec3(std::cos(u), std::sin(u), 0) * (R + sign * 0.5 * s.height) + Vec3(0, 0, z));
    }
  }
  finish(r, s);
  return r;
}

Relief squares_on_cylinder(const ReliefShape& s) {
  // Squares with sharp but smooth corners: superellipses |x|^p + |z|^p = a^p, p = 8 (the distance
  // field (|x|^p + |z|^p)^(1/p) is smooth away from the centre; a Chebyshev max() would put a
  // crease along the diagonals that no real relief has).
  const double R = 1, A1 = 0.6, A2 = 0.45, P = 8;
  Relief r;
  r.mesh = cylinder(R, 2, 400, 128, s.jitter, s.seed);
  auto dist = [&](double x, double y) { return std::pow(std::pow(std::abs(x), P) + std::pow(std::abs(y), P), 1 / P); };
  auto height = [&](double arc, double z) {
    double d1 = dist(arc, z), d2 = dist(std::remainder(arc - M_PI * R, 2 * M_PI * R), z);
    return s.height * step(A1 - d1, s.width) - s.height * step(A2 - d2, s.width);
  };
  emboss_cylinder(r, R, height);
  for (auto [half, center, sign] : {std::tuple{A1, 0.0, 1.0}, std::tuple{A2, M_PI * R, -1.0}})
    for (int k = 0; k < 8000; ++k) {  // superellipse outline: x(z) and z(x) on each side, evenly
      double t = -half + 2 * half * (k % 2000) / 2000.0;
      double o = std::pow(std::pow(half, P) - std::pow(std::abs(t), P), 1 / P);
      double x = 0, z = 0;
      switch (k / 2000) {
        case 0: x = o, z = t; break;
        case 1: x = -o, z = t; break;
        case 2: x = t, z = o; break;
        default: x = t, z = -o; break;
      }
      double u = (center + x) / R;
      r.boundary.push_back(Vec3(std::cos(u), std::sin(u), 0) * (R + sign * 0.5 * s.height) + Vec3(0, 0, z));
    }
  finish(r, s);
  return r;
}

Detection score(const Relief& r, const reliefkit::Polylines& c, double tol) {
  Detection d{0, 0};
  if (r.boundary.empty()) return d;
  // Recall: boundary samples near some curve segment.
  long near = 0;
  for (const auto& b : r.boundary) {
    bool hit = false;
    for (size_t k = 0; k < c.segments.size() && !hit; ++k)
      hit = seg_dist(b, c.points[c.segments[k][0]], c.points[c.segments[k][1]]) <= tol;
    near += hit;
  }
  d.recall = double(near) / r.boundary.size();
  // Precision: curve length (each segment sampled at 4 points) near the boundary samples.
  double total = 0, good = 0;
  for (const auto& s : c.segments) {
    const Vec3 &a = c.points[s[0]], &b = c.points[s[1]];
    double len = (b - a).norm();
    for (int k = 0; k < 4; ++k) {
      Vec3 p = a + (b - a) * ((k + 0.5) / 4);
      double best = 1e300;
      for (const auto& q : r.boundary) best = std::min(best, (p - q).squaredNorm());
      total += len / 4;
      if (std::sqrt(best) <= tol) good += len / 4;
    }
  }
  d.precision = total > 0 ? good / total : 0;
  return d;
}

Relief discs_on_cylinder_of_size(long faces, const ReliefShape& s) {
  const int nz = std::max(8, int(std::sqrt(faces / 2.0 / M_PI)));
  const int nu = std::max(8, int(faces / 2 / nz));
  return discs_on_cylinder(s, nu, nz);
}

}  // namespace rktest

namespace rktest {

std::pair<double, double> axial_line(const AxialFeature& f, int side) {
  switch (f.kind) {
    case AxialFeature::Ridge: return {f.arc, 1 + f.depth};
    case AxialFeature::Valley: return {f.arc, 1 - f.depth};
    case AxialFeature::Band: break;
  }
  return {f.arc + side * f.band, 1 + 0.5 * f.depth};
}

AxialCylinder axial_cylinder(const std::vector<AxialFeature>& features, int nu, double length, double noise,
                             double jitter, uint32_t seed) {
  AxialCylinder c;
  c.features = features;
  c.length = length;
  const int nz = std::max(2, int(std::lround(length / (2 * M_PI / nu))));
  c.mesh = cylinder(1.0, length, nu, nz, jitter, seed);
  auto height = [&](double arc) {
    double z = 0;
    for (const auto& f : features) {
      const double x = std::remainder(arc - f.arc, 2 * M_PI);
      switch (f.kind) {
        case AxialFeature::Ridge: z += f.depth * std::exp(-x * x / (2 * f.width * f.width)); break;
        case AxialFeature::Valley: z -= f.depth * std::exp(-x * x / (2 * f.width * f.width)); break;
        case AxialFeature::Band: z += f.depth * step(x, f.width) * step(f.band - x, f.width); break;
      }
    }
    return z;
  };
  std::vector<Vec3> normal;
  for (auto& p : c.mesh.vertices) {
    const double u = std::atan2(p.y(), p.x());
    const Vec3 n(std::cos(u), std::sin(u), 0);
    normal.push_back(n);
    p += n * height(u);
  }
  c.edge = reliefkit::edge_length_stats(c.mesh).mean;
  Rng rng(seed * 7919 + 13);
  for (size_t i = 0; i < c.mesh.vertices.size(); ++i) c.mesh.vertices[i] += normal[i] * (noise * c.edge * rng.normal());
  return c;
}

AxialScore score_axial(const AxialCylinder& c, const reliefkit::Polylines& curves,
                       const std::vector<AxialFeature::Kind>& kinds, double tol, double margin) {
  struct Line { int feature; Vec3 at; };  // the line's point at z = 0; feature -1: precision only
  std::vector<Line> lines;
  auto wanted = [&](AxialFeature::Kind k) { return std::find(kinds.begin(), kinds.end(), k) != kinds.end(); };
  auto add = [&](int feature, double arc, double r) { lines.push_back({feature, Vec3(r * std::cos(arc), r * std::sin(arc), 0)}); };
  for (int i = 0; i < static_cast<int>(c.features.size()); ++i) {
    const AxialFeature& f = c.features[i];
    if (wanted(f.kind))
      for (int side = 0; side < (f.kind == AxialFeature::Band ? 2 : 1); ++side) {
        const auto [arc, r] = axial_line(f, side);
        add(i, arc, r);
      }
    // A Gaussian valley's banks are ridges of the surface (and a ridge's feet valleys): on the
    // clean surface at ±√3 widths, where the curvature of the opposite sign peaks, and further
    // out the more the detector smooths (at ±3 widths after smoothing by the optimal scale, √2
    // widths). Curves of the opposite kind anywhere in that band are true curves, not false ones.
    const bool banks = (f.kind == AxialFeature::Valley && wanted(AxialFeature::Ridge)) ||
                       (f.kind == AxialFeature::Ridge && wanted(AxialFeature::Valley));
    if (banks) {
      const double r = 1 + (f.kind == AxialFeature::Ridge ? 1 : -1) * f.depth * std::exp(-1.5);
      for (double side : {-1.0, 1.0})
        for (double at = std::sqrt(3.0) * f.width; at <= 3 * f.width + 0.5 * tol; at += 0.5 * tol)
          add(-1, f.arc + side * at, r);
    }
  }
  const double zmax = 0.5 * c.length - margin;
  const int bins = std::max(8, int(2 * zmax / c.edge));  // one per edge length
  auto bin_of = [&](double z) { return std::clamp(int((z + zmax) / (2 * zmax) * bins), 0, bins - 1); };
  std::vector<std::vector<char>> hit(lines.size(), std::vector<char>(bins, 0));
  AxialScore s;
  double good = 0, total = 0;
  for (const auto& seg : curves.segments) {
    const Vec3 &a = curves.points[seg[0]], &b = curves.points[seg[1]];
    for (int k = 0; k < 4; ++k) {
      const Vec3 p = a + (b - a) * ((k + 0.5) / 4);
      if (std::abs(p.z()) > zmax) continue;
      const double len = 0.25 * (b - a).norm();
      total += len;
      bool near = false;
      for (size_t l = 0; l < lines.size(); ++l) {
        const double d = std::hypot(p.x() - lines[l].at.x(), p.y() - lines[l].at.y());
        if (d <= tol) near = true, hit[l][bin_of(p.z())] = 1;
      }
      if (near) good += len;
    }
  }
  s.length = total;
  s.precision = total > 0 ? good / total : 0;
  s.recall.assign(c.features.size(), 0.0);
  std::vector<int> parts(c.features.size(), 0);
  for (size_t l = 0; l < lines.size(); ++l) {
    if (lines[l].feature < 0) continue;
    const double share = std::count(hit[l].begin(), hit[l].end(), 1) / double(bins);
    s.recall[lines[l].feature] += share;
    ++parts[lines[l].feature];
  }
  for (size_t i = 0; i < parts.size(); ++i)
    if (parts[i] > 0) s.recall[i] /= parts[i];
  return s;
}

std::vector<AxialFeature> fine_and_coarse_lines(int around, double fine_width, double coarse_width, double depth) {
  const double h = 2 * M_PI / around;
  std::vector<AxialFeature> lines;
  for (int k = 0; k < 12; ++k) {
    const bool fine = k % 2 == 0;
    lines.push_back({k % 4 < 2 ? AxialFeature::Valley : AxialFeature::Ridge, (k * 150 + 0.37 * k) * h,
                     (fine ? fine_width : coarse_width) * h, depth * h, 0, fine ? 0 : 1});
  }
  return lines;
}

double FineCoarseScore::f1() const {
  const double r = 0.5 * (fine + coarse);
  return r + precision > 0 ? 2 * r * precision / (r + precision) : 0;
}

FineCoarseScore score_fine_coarse(const AxialCylinder& c, const reliefkit::Polylines& ridges,
                                  const reliefkit::Polylines& valleys, double tol, double margin) {
  const AxialScore sv = score_axial(c, valleys, {AxialFeature::Valley}, tol, margin);
  const AxialScore sr = score_axial(c, ridges, {AxialFeature::Ridge}, tol, margin);
  FineCoarseScore s;
  int nf = 0, nc = 0;
  for (size_t i = 0; i < c.features.size(); ++i) {
    const double r = c.features[i].kind == AxialFeature::Valley ? sv.recall[i] : sr.recall[i];
    (c.features[i].group == 0 ? s.fine : s.coarse) += r;
    ++(c.features[i].group == 0 ? nf : nc);
  }
  if (nf > 0) s.fine /= nf;
  if (nc > 0) s.coarse /= nc;
  const double len = sv.length + sr.length;
  s.precision = len > 0 ? (sv.precision * sv.length + sr.precision * sr.length) / len : 0;
  return s;
}

}  // namespace rktest
