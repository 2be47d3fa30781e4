// The bad-input cases every filter must survive, run through meshlabserver: a point cloud, an
// empty mesh and NaN coordinates must give a clear message; non-manifold, degenerate and
// isolated elements, and a flat plane, a successful run. Never a crash.
#pragma once

#include <functional>
#include <string>

#include "reliefkit/base/mesh.h"
#include "server.h"

namespace rktest {

using FilterRun = std::function<ServerRun(const std::string& name, const reliefkit::TriMesh& mesh)>;

/// Runs all the cases with `run` and records gtest failures. `flat_refusal`: for a filter whose
/// input must have a shape (a vessel's axis), the message the flat plane must be refused with,
/// instead of a successful run. `damaged_refusal`: likewise for the damaged mesh (a relief disc on
/// a plane), for a filter that needs a wall round an axis: its repair is logged, then the refusal.
void expect_bad_input_handled(const FilterRun& run, const std::string& flat_refusal = "", const std::string& damaged_refusal = "");

}  // namespace rktest
