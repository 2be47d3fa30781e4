#include "mesh_bridge.h"

#include <cmath>

namespace reliefkit::ml {

View view_of(MeshModel& m) {
  View v = from_vcg(m.cm);
  require_triangles(v.mesh);
  return v;
}

void write_vertex_attribute(CMeshO& m, const View& v, const char* name, const std::vector<double>& values) {
  auto h = vcg::tri::Allocator<CMeshO>::GetPerVertexAttribute<Scalarm>(m, std::string(name));
  for (size_t i = 0; i < v.vertex_of.size() && i < values.size(); ++i) h[v.vertex_of[i]] = Scalarm(values[i]);
}

double mean_edge_length(MeshModel& m) {
  double sum = 0;
  long long n = 0;
  for (const auto& f : m.cm.face) {
    if (f.IsD()) continue;
    for (int j = 0; j < 3; ++j) {
      double l = double(vcg::Distance(f.cV(j)->cP(), f.cV((j + 1) % 3)->cP()));
      if (std::isfinite(l)) sum += l, ++n;
    }
  }
  if (n > 0 && sum > 0) return sum / n;
  double diag = m.cm.bbox.Diag();
  return std::isfinite(diag) && diag > 0 ? diag / 100 : 1.0;
}

QString thousands(long long n) {
  QString s = QString::number(n < 0 ? -n : n);
  for (int i = s.size() - 3; i > 0; i -= 3) s.insert(i, ',');
  return n < 0 ? "-" + s : s;
}

}  // namespace reliefkit::ml
