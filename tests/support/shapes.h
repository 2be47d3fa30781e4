// Analytic test surfaces with known curvature, as ReliefKit TriMesh. "Jittered" meshes move
// every vertex in the parameter domain by up to `jitter` grid cells (uniformly, seeded) while
// keeping it exactly on the surface, so the triangulation is irregular but the answer is exact.
#pragma once

#include <cstdint>
#include <functional>
#include <random>

#include "reliefkit/base/mesh.h"

namespace rktest {

using reliefkit::TriMesh;
using reliefkit::Vec3;

// Torus around z: big radius R, tube radius r; nu cells around z, nv around the tube.
// Outward normal; k1 = 1/r, k2 = cos v / (R + r cos v).
TriMesh torus(double R, double r, int nu, int nv, double jitter = 0, uint32_t seed = 1);
void torus_params(double R, double r, const Vec3& p, double& u, double& v);

// Sphere of radius r: a subdivided icosahedron projected on the sphere (levels >= 0).
TriMesh sphere(double r, int levels, double jitter = 0, uint32_t seed = 1);

/// Three draws of `gauss` as a vector, z drawn first and x last: the order GCC gave
/// Vec3(gauss(rng), gauss(rng), gauss(rng)) when the generators' known answers were measured (C++
/// leaves a call's argument order open; clang draws x first).
Vec3 gauss_vec3(std::normal_distribution<double>& gauss, std::mt19937& rng);

/// Moves `mesh` by a random rotation and a translation of about `spread` per coordinate (the
/// generators' random pose; `gauss` draws from `rng`), and the axis (point, direction) with it.
void place_randomly(TriMesh& mesh, Vec3& axis_point, Vec3& axis_direction, std::mt19937& rng,
                    std::normal_distribution<double>& gauss, double spread);

// Open cylinder of radius r around z, height h; k1 = 1/r, k2 = 0.
TriMesh cylinder(double r, double h, int nu, int nz, double jitter = 0, uint32_t seed = 1);

// Height field z = f(x, y) on [-half, half]^2 with n x n cells, normal +z. The vertex at the
// origin is never jittered (index returned through `origin_index`).
TriMesh height_field(const std::function<double(double, double)>& f, double half, int n, double jitter = 0,
                     uint32_t seed = 1, int* origin_index = nullptr);

// Benchmark surface: a torus (R = 3, r = 1) with bumps of 5 % of the tube radius, jittered
// triangulation, about `faces` faces.
TriMesh relief_torus(long faces);

// Small deterministic RNG (uniform in [0,1), Box-Muller normals).
struct Rng {
  uint64_t s;
  explicit Rng(uint64_t seed) : s(seed * 0x9E3779B97F4A7C15ull + 1) {}
  double uniform();
  double normal();
};

double median(std::vector<double> v);
double percentile(std::vector<double> v, double q);

/// Distance from each point to the nearest point of the mesh's surface (its triangles), for points
/// within `reach` of it; farther points get +infinity. A uniform grid of cells of size `reach`
/// (at least the longest edge) keeps it linear.
std::vector<double> distance_to_surface(const reliefkit::TriMesh& mesh, const std::vector<reliefkit::Vec3>& points,
                                        double reach);

}  // namespace rktest
