// Chapter 5's multi-scale curves against the single-scale ones, at the filters' defaults, on real
// scans (issue 22, point 1): for each scan, the share of the single-scale relief edges' length
// that has a multi-scale relief edge within 2 edge lengths ("kept"), the multi-scale length with
// no single-scale edge within 2 edge lengths ("added"), and for ridges and valleys the share of
// the length in pieces shorter than 10 edge lengths (dashes), single and multi-scale; times.
//   build/bench/bench_multiscale_scans scan.ply ...
// `python3 bench/compare_meshlab.py scans` runs it on ../shared/data and on decimated copies.
#include <omp.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "bench_util.h"
#include "mesh_files.h"
#include "reliefkit/base/curve_selection.h"
#include "reliefkit/base/surface.h"
#include "reliefkit/multiscale/multiscale.h"

using namespace reliefkit;

namespace {

// The length of `of`'s segments whose midpoints lie within r of a segment of `by`.
double length_within(const Polylines& of, const Polylines& by, double r) {
  const std::vector<char> near = segments_near(of, by, r);
  double within = 0;
  for (size_t k = 0; k < of.segments.size(); ++k)
    if (near[k]) within += (of.points[of.segments[k][1]] - of.points[of.segments[k][0]]).norm();
  return within;
}

double short_share(const Polylines& p, double edge) {
  double all = 0, dashes = 0;
  for (const auto& ch : p.chains()) {
    double l = 0;
    for (size_t i = 1; i < ch.size(); ++i) l += (p.points[ch[i]] - p.points[ch[i - 1]]).norm();
    all += l;
    if (l < 10 * edge) dashes += l;
  }
  return all > 0 ? dashes / all : 0;
}

OptimalScaleOptions filter_defaults() {
  OptimalScaleOptions o;  // as the filters resolve "auto": 1 to 16 edge lengths, lowered on small objects
  o.max_scale_auto = true;
  return o;
}

void relief_edges_row(const std::string& name, const Surface& surface) {
  const double h = surface.scale().edge;
  double t0 = rkbench::now();
  const ReliefEdgeResult single = compute_relief_edges(surface);
  const double t_single = rkbench::now() - t0;
  t0 = rkbench::now();
  const MultiscaleReliefEdges multi = multiscale_relief_edges(surface, filter_defaults());
  const double t_multi = rkbench::now() - t0;
  const double ls = single.edges.total_length(), lm = multi.curves.edges.total_length();
  const double kept = ls > 0 ? length_within(single.edges, multi.curves.edges, 2 * h) / ls : 0;
  const double added = lm - length_within(multi.curves.edges, single.edges, 2 * h);
  std::printf("%-30s relief edges     single %8.0f e  multi %8.0f e  kept %.3f  added %7.0f e  time %6.2f / %6.2f s\n",
              name.c_str(), ls / h, lm / h, kept, added / h, t_single, t_multi);
}

void ridges_row(const std::string& name, const Surface& surface) {
  const double h = surface.scale().edge;
  double t0 = rkbench::now();
  const RidgeValleyResult single = compute_ridges_valleys(surface);
  const double t_single = rkbench::now() - t0;
  t0 = rkbench::now();
  RidgeValleyParams params;  // as the filter's default
  params.min_length_edges = kMultiscaleMinLengthEdges;
  const MultiscaleRidgeValleys multi = multiscale_ridges_valleys(surface, filter_defaults(), params);
  const double t_multi = rkbench::now() - t0;
  for (bool valleys : {false, true}) {
    const Polylines& s = valleys ? single.valleys : single.ridges;
    const Polylines& m = valleys ? multi.curves.valleys : multi.curves.ridges;
    std::printf("%-30s %-16s single %8.0f e  multi %8.0f e  dashes %.3f / %.3f  kept %.3f  time %6.2f / %6.2f s\n",
                name.c_str(), valleys ? "valleys" : "ridges", s.total_length() / h, m.total_length() / h,
                short_share(s, h), short_share(m, h),
                s.total_length() > 0 ? length_within(s, m, 2 * h) / s.total_length() : 0, t_single, t_multi);
  }
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: bench_multiscale_scans scan.ply ...\n");
    return 2;
  }
  std::printf("Single- vs multi-scale curves at defaults, %d threads (lengths in edge lengths e; kept: share of\n"
              "the single-scale length with a multi-scale curve within 2 e; dashes: share in pieces < 10 e)\n",
              omp_get_max_threads());
  for (int i = 1; i < argc; ++i) {
    const std::string path = argv[i], name = path.substr(path.find_last_of('/') + 1);
    TriMesh m;
    if (!rkbench::read_scan(path, m)) continue;
    const Surface surface = Surface::borrow(m);
    relief_edges_row(name, surface);
    ridges_row(name, surface);
  }
  return 0;
}
