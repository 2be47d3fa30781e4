#include "flakes.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>

#include "shapes.h"

using reliefkit::TriMesh;
using reliefkit::Vec3;

namespace rktest {
namespace {

constexpr double kA = 1.0, kB = 0.65;  // the outline's half axes
constexpr double kDome = 0.30;         // the blank's height over the outline's plane
constexpr double kVentral = 0.05;      // the ventral face's bulge

struct Scar {
  double cx, cy, bottom, radius;  // the bowl
  double qx, qy;                  // its point of percussion, on the outline
};

// The dorsal surfaces: 0 the blank (cortex, rough), k >= 1 the bowl of scar k - 1 (rippled).
struct Dorsal {
  std::vector<Scar> scars;
  double h = 0, ripple = 0, rough = 0;
  double wave_kx[8], wave_ky[8], wave_phase[8];

  double blank(double x, double y) const {
    const double r2 = (x / kA) * (x / kA) + (y / kB) * (y / kB);
    double bumps = 0;
    for (int j = 0; j < 8; ++j) bumps += std::sin(wave_kx[j] * x + wave_ky[j] * y + wave_phase[j]);
    return kDome * (1 - r2) + rough * bumps / std::sqrt(8.0);
  }
  double surface(int k, double x, double y) const {
    if (k == 0) return blank(x, y);
    const Scar& s = scars[size_t(k - 1)];
    const double d2 = (x - s.cx) * (x - s.cx) + (y - s.cy) * (y - s.cy);
    const double from_percussion = std::hypot(x - s.qx, y - s.qy);
    return s.bottom + d2 / (2 * s.radius) + ripple * std::sin(2 * M_PI * from_percussion / (8 * h));
  }
  int lowest(double x, double y) const {
    int best = 0;
    for (int k = 1; k <= int(scars.size()); ++k)
      if (surface(k, x, y) < surface(best, x, y)) best = k;
    return best;
  }
  double z(double x, double y) const { return surface(lowest(x, y), x, y); }
};

Dorsal make_dorsal(const FlakeShape& s, double h, Rng& rng) {
  Dorsal d;
  d.h = h, d.ripple = s.ripple * h, d.rough = s.roughness * h;
  for (int j = 0; j < 8; ++j) {
    const double angle = 2 * M_PI * rng.uniform(), wavelength = (6 + 6 * rng.uniform()) * h;
    d.wave_kx[j] = 2 * M_PI / wavelength * std::cos(angle);
    d.wave_ky[j] = 2 * M_PI / wavelength * std::sin(angle);
    d.wave_phase[j] = 2 * M_PI * rng.uniform();
  }
  for (int i = 0; i < s.scars; ++i) {
    const double phi = 2 * M_PI * (i + 0.3 * rng.uniform()) / s.scars;
    Scar c;
    c.qx = kA * std::cos(phi), c.qy = kB * std::sin(phi);
    const double inward = 0.35 + 0.2 * rng.uniform();
    c.cx = c.qx * (1 - inward), c.cy = c.qy * (1 - inward);
    c.radius = 1.2 + 0.8 * rng.uniform();
    c.bottom = kDome * (1 - (1 - inward) * (1 - inward)) - (0.08 + 0.06 * rng.uniform());
    d.scars.push_back(c);
  }
  return d;
}

// The square [-1, 1]² onto the ellipse (the elliptical grid mapping: smooth, no pole).
void to_outline(double u, double v, double& x, double& y) {
  x = kA * u * std::sqrt(1 - v * v / 2);
  y = kB * v * std::sqrt(1 - u * u / 2);
}

// The ventral face: a shallow bulge whose rim follows the dorsal face's rim.
double ventral(const Dorsal& d, double x, double y) {
  const double r2 = (x / kA) * (x / kA) + (y / kB) * (y / kB);
  const double theta = std::atan2(y / kB, x / kA);
  return -kVentral * (1 - r2) + r2 * d.z(kA * std::cos(theta), kB * std::sin(theta));
}

// The arêtes: where neighbouring points of a fine grid lie on different surfaces, the crossing
// found by bisection.
std::vector<Vec3> arete_samples(const Dorsal& d, double step) {
  std::vector<Vec3> out;
  auto inside = [](double x, double y) { return (x / kA) * (x / kA) + (y / kB) * (y / kB) < 1; };
  auto crossing = [&](double x0, double y0, double x1, double y1, int a, int b) {
    double lo = 0, hi = 1;
    for (int it = 0; it < 30; ++it) {
      const double t = 0.5 * (lo + hi), x = x0 + t * (x1 - x0), y = y0 + t * (y1 - y0);
      (d.surface(a, x, y) < d.surface(b, x, y) ? lo : hi) = t;
    }
    const double x = x0 + lo * (x1 - x0), y = y0 + lo * (y1 - y0);
    out.emplace_back(x, y, d.z(x, y));
  };
  for (double x = -kA; x <= kA; x += step)
    for (double y = -kB; y <= kB; y += step) {
      if (!inside(x, y)) continue;
      const int here = d.lowest(x, y);
      for (const auto& [dx, dy] : {std::pair{step, 0.0}, std::pair{0.0, step}}) {
        if (!inside(x + dx, y + dy)) continue;
        const int there = d.lowest(x + dx, y + dy);
        if (there != here) crossing(x, y, x + dx, y + dy, here, there);
      }
    }
  return out;
}

}  // namespace

Flake knapped_flake(const FlakeShape& s) {
  Rng rng(s.seed);
  const int n = s.cells;
  const double h = 2 * kA / n * 0.85;  // about the mean edge length the mapping gives
  const Dorsal d = make_dorsal(s, h, rng);
  Flake f;
  TriMesh& m = f.relief.mesh;
  // Dorsal grid, then the ventral grid's interior (its rim is the dorsal rim).
  std::vector<int> dorsal_index((n + 1) * (n + 1)), ventral_index((n + 1) * (n + 1));
  for (int face = 0; face < 2; ++face)
    for (int i = 0; i <= n; ++i)
      for (int j = 0; j <= n; ++j) {
        const bool rim = i == 0 || j == 0 || i == n || j == n;
        if (face == 1 && rim) {
          ventral_index[i * (n + 1) + j] = dorsal_index[i * (n + 1) + j];
          continue;
        }
        double u = -1 + 2.0 * i / n, v = -1 + 2.0 * j / n;
        if (!rim) u += s.jitter * (2.0 / n) * (rng.uniform() - 0.5), v += s.jitter * (2.0 / n) * (rng.uniform() - 0.5);
        double x, y;
        to_outline(u, v, x, y);
        (face == 0 ? dorsal_index : ventral_index)[i * (n + 1) + j] = m.n_vertices();
        m.vertices.emplace_back(x, y, face == 0 ? d.z(x, y) : ventral(d, x, y));
      }
  for (int face = 0; face < 2; ++face) {
    const std::vector<int>& id = face == 0 ? dorsal_index : ventral_index;
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j) {
        const int a = id[i * (n + 1) + j], b = id[(i + 1) * (n + 1) + j], c = id[(i + 1) * (n + 1) + j + 1],
                  e = id[i * (n + 1) + j + 1];
        // The diagonal a-c, unless it joins two rim vertices (two corners of the square): the
        // triangle of three rim vertices would be both faces' at once.
        const bool rim_diagonal = (i == 0 && j == n - 1) || (i == n - 1 && j == 0);
        std::array<std::array<int, 3>, 2> t = rim_diagonal ? std::array<std::array<int, 3>, 2>{{{a, b, e}, {b, c, e}}}
                                                           : std::array<std::array<int, 3>, 2>{{{a, b, c}, {a, c, e}}};
        for (auto& tri : t) {
          if (face == 1) std::swap(tri[1], tri[2]);
          m.faces.push_back(tri);
        }
      }
  }
  f.relief.mean_edge = reliefkit::edge_length_stats(m).mean;
  for (auto& p : m.vertices)
    for (int k = 0; k < 3; ++k) p[k] += s.noise * f.relief.mean_edge * rng.normal();
  f.relief.boundary = arete_samples(d, h / 4);
  for (int k = 0; k < 8 * n; ++k) {
    const double theta = 2 * M_PI * k / (8 * n), x = kA * std::cos(theta), y = kB * std::sin(theta);
    f.edge.emplace_back(x, y, d.z(x, y));
  }
  return f;
}

FlakeScore score_flake(const Flake& f, const reliefkit::Polylines& curves, double tolerance) {
  Relief lines = f.relief, edge = f.relief;
  lines.boundary.insert(lines.boundary.end(), f.edge.begin(), f.edge.end());
  edge.boundary = f.edge;
  return {score(f.relief, curves, tolerance).recall, score(lines, curves, tolerance).precision,
          score(edge, curves, tolerance).recall};
}

}  // namespace rktest
