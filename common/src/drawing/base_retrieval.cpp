// ReliefKit — retrieval of the base model (thesis sect. 7.5): the 48 ways a model's principal
// axes can face the views, and the library ranked by the distance of their silhouette features.
// See base_library.h.
#include <algorithm>
#include <cstdlib>

#include "reliefkit/drawing/base_library.h"
#include "silhouette_raster.h"

namespace reliefkit {

bool AxisOrientation::mirrors() const {
  const bool odd = (axis[0] > axis[1]) ^ (axis[0] > axis[2]) ^ (axis[1] > axis[2]);
  return odd ^ ((sign[0] * sign[1] * sign[2]) < 0);
}

TriMesh oriented(const TriMesh& mesh, const AxisOrientation& o) {
  TriMesh out = mesh;
  for (auto& p : out.vertices) p = o.apply(p);
  if (o.mirrors())
    for (auto& f : out.faces) std::swap(f[1], f[2]);
  return out;
}

std::vector<AxisOrientation> all_axis_orientations() {
  std::vector<AxisOrientation> out;
  std::array<int, 3> perm{0, 1, 2};
  do {
    for (int s = 0; s < 8; ++s) {
      AxisOrientation o;
      o.axis = perm;
      o.sign = {(s & 1) ? -1 : 1, (s & 2) ? -1 : 1, (s & 4) ? -1 : 1};
      out.push_back(o);
    }
  } while (std::next_permutation(perm.begin(), perm.end()));
  return out;
}

SilhouetteFeature oriented_feature(const LibraryModel& model, const AxisOrientation& o, ViewKind view) {
  const auto axes = silhouette::view_axes(view);  // signed world axes of the view's coordinates
  const int ia = std::abs(axes[0]) - 1, ib = std::abs(axes[1]) - 1;
  const int sa = (axes[0] > 0 ? 1 : -1) * o.sign[size_t(ia)], sb = (axes[1] > 0 ? 1 : -1) * o.sign[size_t(ib)];
  const int p = o.axis[size_t(ia)], q = o.axis[size_t(ib)];
  const int depth = 3 - p - q;
  return transform_feature(model.feature[size_t(depth)], p > q, sa < 0, sb < 0);
}

std::vector<BaseMatch> retrieve_bases(const BaseLibrary& library, const std::vector<ViewFeature>& views, int top) {
  if (views.empty()) throw InputError("No view of the drawing to compare with the library.");
  const auto orientations = all_axis_orientations();
  std::vector<BaseMatch> best(library.models.size());
#pragma omp parallel for schedule(static)
  for (long i = 0; i < long(library.models.size()); ++i) {
    BaseMatch b;
    b.model = int(i);
    b.score = 1e300;
    for (const auto& o : orientations) {
      double s = 0;
      for (const auto& v : views) s += feature_distance(v.feature, oriented_feature(library.models[size_t(i)], o, v.kind));
      s /= double(views.size());
      if (s < b.score) { b.score = s; b.orientation = o; }
    }
    best[size_t(i)] = b;
  }
  std::sort(best.begin(), best.end(), [](const BaseMatch& a, const BaseMatch& b) {
    return a.score != b.score ? a.score < b.score : a.model < b.model;
  });
  if (int(best.size()) > top) best.resize(size_t(std::max(top, 1)));
  return best;
}

BaseMatch named_match(const BaseLibrary& library, const std::vector<BaseMatch>& ranked, const std::string& name) {
  const std::string wanted = silhouette::lower(name);
  for (const auto& m : ranked)
    if (silhouette::lower(library.models[size_t(m.model)].name) == wanted) return m;
  throw InputError("\"Use model\": no model named \"" + name + "\" in the library (names as the log lists them" +
                   (ranked.empty() ? std::string(").") : ", e.g. " + library.models[size_t(ranked.front().model)].name + ")."));
}
}  // namespace reliefkit
