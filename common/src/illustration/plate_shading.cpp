// ReliefKit — the plate's headless shadings (issue 44): raking and multi-directional light,
// openness (the sky-view factor), radiance scaling, and the light stack with its .lp file. See
// plate.h.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <unordered_map>

#include "plate_raster.h"
#include "reliefkit/base/angles.h"
#include "reliefkit/base/scale.h"
#include "reliefkit/illustration/plate.h"

namespace reliefkit {
namespace {


// The view's page axes: right, up, and towards the viewer.
struct ViewAxes {
  Vec3 right, up, towards;
};
ViewAxes view_axes(const PlateView& view) {
  ViewAxes a;
  a.towards = -view.direction.normalized();
  Vec3 up = view.up - view.up.dot(a.towards) * a.towards;
  if (up.norm() < 1e-9) up = a.towards.unitOrthogonal();
  a.up = up.normalized();
  a.right = a.up.cross(a.towards);
  return a;
}

std::vector<double> lit(const std::vector<Vec3>& normals, const Vec3& light) {
  std::vector<double> g(normals.size());
  for (size_t i = 0; i < g.size(); ++i) g[i] = std::max(0.0, normals[i].dot(light));
  return g;
}

// What a face square to the view shows: light grey, so that faces turned to the light can be
// brighter and faces turned away darker (a raking light's flat face is otherwise dark: sin 20° = 0.34).
constexpr double kFlatGrey = 0.65;

// Raking: the light received, scaled so that a face square to the view is kFlatGrey.
std::vector<double> raking(const std::vector<Vec3>& normals, const PlateView& view, const PlateShadingParams& p) {
  std::vector<double> g = lit(normals, light_direction(view, p.azimuth_deg, p.elevation_deg));
  for (double& x : g) x = std::min(1.0, kFlatGrey * x / std::sin(p.elevation_deg * kRadiansPerDegree));
  return g;
}

// Lights from `directions` azimuths at 45 degrees, averaged: the cosine of the face's tilt from
// the view up to 45 degrees (each direction's slope term cancels in the mean), less beyond (a
// silhouette 0.32) — a slope shading with no direction favoured; its cube, so that tilts of
// 20-45 degrees read (0.83 to 0.35 of the flat face's 0.9). At the raking elevation (20) the steep
// faces still caught light from their side and the silhouettes stayed light grey (seen on the
// gargoyle).
constexpr double kMultiElevationDeg = 45;
std::vector<double> multi_directional(const std::vector<Vec3>& normals, const PlateView& view, const PlateShadingParams& p) {
  std::vector<double> g(normals.size(), 0);
  const double flat = std::sin(kMultiElevationDeg * kRadiansPerDegree);  // what a face square to the view receives from each
  for (int k = 0; k < p.directions; ++k) {
    const std::vector<double> one = lit(normals, light_direction(view, p.azimuth_deg + 360.0 * k / p.directions, kMultiElevationDeg));
    for (size_t i = 0; i < g.size(); ++i) g[i] += one[i] / (p.directions * flat);
  }
  for (double& x : g) x = 0.9 * std::pow(std::min(1.0, x), 3);
  return g;
}

// Vertices hashed into cubes of side `cell`, for the neighbours within a radius.
class VertexGrid {
 public:
  VertexGrid(const std::vector<Vec3>& points, double cell) : points_(points), cell_(cell) {
    for (size_t i = 0; i < points.size(); ++i) cells_[key(points[i])].push_back(int(i));
  }
  template <class Visit>
  void near(const Vec3& p, Visit visit) const {
    const long x = coord(p.x()), y = coord(p.y()), z = coord(p.z());
    for (long dx = -1; dx <= 1; ++dx)
      for (long dy = -1; dy <= 1; ++dy)
        for (long dz = -1; dz <= 1; ++dz) {
          const auto it = cells_.find(pack(x + dx, y + dy, z + dz));
          if (it != cells_.end())
            for (int i : it->second) visit(i);
        }
  }

 private:
  long coord(double v) const { return long(std::floor(v / cell_)); }
  static long long pack(long x, long y, long z) { return ((long long)(x & 0x1FFFFF) << 42) | ((long long)(y & 0x1FFFFF) << 21) | (z & 0x1FFFFF); }
  long long key(const Vec3& p) const { return pack(coord(p.x()), coord(p.y()), coord(p.z())); }
  const std::vector<Vec3>& points_;
  double cell_;
  std::unordered_map<long long, std::vector<int>> cells_;
};

// The sky-view factor of each vertex: in 16 sectors round its normal, the highest elevation at
// which the surface within the radius rises above its tangent plane (0 when none does), and the
// share of the sky's hemisphere above those horizons, 1 - sin(horizon), averaged (Zakšek et al. 2011).
std::vector<double> openness(const Surface& surface, double radius) {
  constexpr int kSectors = 16;
  const auto& points = surface.mesh().vertices;
  const auto& normals = surface.normals();
  const VertexGrid grid(points, radius);
  std::vector<double> g(points.size(), 1);
#pragma omp parallel for schedule(dynamic, 256)
  for (long i = 0; i < long(points.size()); ++i) {
    const Vec3 p = points[size_t(i)], n = normals[size_t(i)];
    if (!(n.norm() > 0)) continue;
    const Vec3 t1 = n.unitOrthogonal(), t2 = n.cross(t1);
    double horizon[kSectors] = {0};  // per sector, the tangent of the horizon's elevation
    grid.near(p, [&](int j) {  // the horizon as its tangent, rises under 0.6 degrees left out (sin < 0.01)
      const Vec3 d = points[size_t(j)] - p;
      const double h = d.dot(n);
      if (h <= 0 || d.squaredNorm() > radius * radius) return;
      const double along1 = d.dot(t1), along2 = d.dot(t2), rho = std::sqrt(along1 * along1 + along2 * along2);
      if (!(h > 0.01 * rho)) return;
      const int sector = std::min(kSectors - 1, int((std::atan2(along2, along1) + M_PI) / (2 * M_PI) * kSectors));
      horizon[sector] = std::max(horizon[sector], h / rho);
    });
    double sky = 0;
    for (double rise : horizon) sky += (1 - rise / std::sqrt(1 + rise * rise)) / kSectors;  // 1 - sin(atan(rise))
    g[size_t(i)] = sky;
  }
  return g;
}

// Light from the top left, scaled by the mean curvature H (convex positive, from the cotangent
// Laplacian: the Laplace-Beltrami of the positions is -2 H n): 1 + strength tanh(H / (3 median |H|)) / 2.
std::vector<double> radiance_scaling(const Surface& surface, const PlateView& view, const PlateShadingParams& p) {
  const auto& points = surface.mesh().vertices;
  const auto& normals = surface.normals();
  const LaplacianResult& lap = surface.laplacian();
  Eigen::MatrixXd x(points.size(), 3);
  for (size_t i = 0; i < points.size(); ++i) x.row(long(i)) = points[i].transpose();
  const Eigen::MatrixXd lx = lap.L * x;
  std::vector<double> h(points.size(), 0), magnitude;
  for (size_t i = 0; i < points.size(); ++i) {
    const double area = lap.mass[long(i)];
    if (area > 0) h[i] = -0.5 * Vec3(lx.row(long(i)).transpose()).dot(normals[i]) / area;
    magnitude.push_back(std::abs(h[i]));
  }
  const double typical = std::max(percentile(magnitude, 0.5), 1e-300);
  const std::vector<double> light = lit(normals, light_direction(view, 315, 45));
  std::vector<double> g(points.size());
  for (size_t i = 0; i < g.size(); ++i)
    g[i] = std::clamp((0.25 + 0.75 * light[i]) * (1 + 0.5 * p.strength * std::tanh(h[i] / (3 * typical))), 0.0, 1.0);
  return g;
}

}  // namespace

void PlateShadingParams::validate() const {
  if (!std::isfinite(azimuth_deg)) throw InputError("The light's azimuth must be a number of degrees.");
  if (!(elevation_deg > 0 && elevation_deg <= 90)) throw InputError("The light's elevation must be above 0 and at most 90 degrees.");
  if (!(directions >= 1 && directions <= 360)) throw InputError("The number of light directions must be from 1 to 360.");
  if (!(radius_edges > 0 && radius_edges <= 1000)) throw InputError("The openness radius must be from above 0 to 1000 edge lengths.");
  if (!(strength >= 0 && strength <= 10)) throw InputError("The radiance scaling's strength must be from 0 to 10.");
}

Vec3 light_direction(const PlateView& view, double azimuth_deg, double elevation_deg) {
  const ViewAxes a = view_axes(view);
  const double az = azimuth_deg * kRadiansPerDegree, el = elevation_deg * kRadiansPerDegree;
  return (std::cos(el) * (std::sin(az) * a.right + std::cos(az) * a.up) + std::sin(el) * a.towards).normalized();
}

std::vector<double> plate_shading(const Surface& surface, const PlateView& view, const PlateShadingParams& p) {
  p.validate();
  surface.require_triangles();
  switch (p.kind) {
    case PlateShadingKind::raking:
      return raking(surface.normals(), view, p);
    case PlateShadingKind::multi_directional:
      return multi_directional(surface.normals(), view, p);
    case PlateShadingKind::openness:
      require_usable_scale(surface.scale());
      return openness(surface, p.radius_edges * surface.scale().edge);
    case PlateShadingKind::radiance_scaling:
      return radiance_scaling(surface, view, p);
  }
  return {};
}

LightStack light_stack(const Surface& surface, const PlateView& view, const PlateParams& params, double ratio, int count,
                       double elevation_deg) {
  if (!(count >= 1 && count <= 360)) throw InputError("A light stack has from 1 to 360 images.");
  PlateShadingParams p;
  p.elevation_deg = elevation_deg;
  p.validate();
  const PageFrame frame = at_ratio(page_frame(surface.mesh(), view, params.unit_mm), ratio);
  const ViewAxes axes = view_axes(view);
  LightStack stack;
  for (int k = 0; k < count; ++k) {
    p.azimuth_deg = 360.0 * k / count;
    const Vec3 light = light_direction(view, p.azimuth_deg, elevation_deg);
    stack.images.push_back(rasterize(surface.mesh(), plate_shading(surface, view, p), frame, params).grey);
    stack.directions.push_back(Vec3(light.dot(axes.right), light.dot(axes.up), light.dot(axes.towards)));
  }
  return stack;
}

std::string lp_file(const std::vector<std::string>& image_names, const std::vector<Vec3>& directions) {
  std::string text = std::to_string(image_names.size()) + "\n";
  char line[64];
  for (size_t k = 0; k < image_names.size() && k < directions.size(); ++k) {
    std::snprintf(line, sizeof line, " %.6f %.6f %.6f\n", directions[k].x(), directions[k].y(), directions[k].z());
    text += image_names[k] + line;
  }
  return text;
}

}  // namespace reliefkit
