// Minimal PLY / OBJ reading and writing for tests and benchmarks (the formats meshlabserver
// reads and writes: PLY ascii or binary little-endian, OBJ with v / f / l records).
#pragma once

#include <map>
#include <string>
#include <vector>

#include "reliefkit/base/mesh.h"
#include "reliefkit/base/zero_crossings.h"

namespace rktest {

struct MeshFile {
  reliefkit::TriMesh mesh;
  std::map<std::string, std::vector<double>> vertex_props;  // every non-coordinate vertex property
  std::vector<std::array<int, 2>> edges;                     // OBJ 'l' records / PLY edge elements
};

/// Reads a PLY or OBJ file (by extension). Throws std::runtime_error on failure.
MeshFile read_mesh(const std::string& path);

/// The edges of a saved curve layer as polylines (strength 1 everywhere), for scoring.
reliefkit::Polylines polylines_of(const MeshFile& curves);

/// Share of the length of the curves (edges) of `a` within `tol` of a segment of `b`: 1 when every
/// piece of `a` lies near `b` (recall of `b` against `a`, or precision the other way round).
double near_share(const MeshFile& a, const MeshFile& b, double tol);

/// Writes a binary little-endian PLY with float coordinates (NaNs are written as they are).
void write_ply(const std::string& path, const reliefkit::TriMesh& mesh);

}  // namespace rktest
