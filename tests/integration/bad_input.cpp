#include "bad_input.h"

#include <gtest/gtest.h>

#include <limits>

#include "reliefs.h"
#include "shapes.h"

namespace rktest {

void expect_bad_input_handled(const FilterRun& run, const std::string& flat_refusal, const std::string& damaged_refusal) {
  auto expect_message = [&](const std::string& name, const reliefkit::TriMesh& m, const std::string& text) {
    ServerRun r = run(name, m);
    EXPECT_FALSE(r.crashed) << name << ": " << r.output;
    EXPECT_NE(r.output.find(text), std::string::npos) << name << ": " << r.output;
  };
  auto expect_success = [&](const std::string& name, const reliefkit::TriMesh& m) {
    ServerRun r = run(name, m);
    EXPECT_FALSE(r.crashed) << name << ": " << r.output;
    EXPECT_EQ(r.status, 0) << name << ": " << r.output;
  };
  reliefkit::TriMesh cloud = sphere(1, 2);
  cloud.faces.clear();
  expect_message("pointcloud", cloud, "point cloud");
  expect_message("empty", reliefkit::TriMesh{}, "empty mesh");
  reliefkit::TriMesh nan = sphere(1, 3);
  nan.vertices[3].z() = std::numeric_limits<double>::quiet_NaN();
  expect_message("nan", nan, "NaN");
  reliefkit::TriMesh m = disc_on_plane({}, 60).mesh;
  m.vertices.push_back({0, 0, 1});
  m.faces.push_back({m.faces[10][0], m.faces[10][1], m.n_vertices() - 1});  // non-manifold edge
  m.faces.push_back({5, 5, 6});                                              // repeated vertex
  m.vertices.push_back(m.vertices[7]);
  m.faces.push_back({7, m.n_vertices() - 1, 7});  // zero area
  m.vertices.push_back({9, 9, 9});                // isolated vertex
  if (damaged_refusal.empty()) {
    expect_success("nonmanifold", m);
  } else {
    expect_message("nonmanifold", m, "Repaired for the computation");
    expect_message("nonmanifold_refused", m, damaged_refusal);
  }
  const reliefkit::TriMesh flat = height_field([](double, double) { return 0.0; }, 1.0, 30, 0.3);
  if (flat_refusal.empty()) expect_success("flat", flat);
  else expect_message("flat", flat, flat_refusal);
}

}  // namespace rktest
