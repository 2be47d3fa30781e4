#include "mesh_bridge.h"

#include "reliefkit/rollout/unroll.h"

#include <vcg/complex/append.h>

#include <algorithm>
#include <cmath>

namespace reliefkit::ml {

View view_of(MeshModel& m, const std::function<void(const QString&)>& log) {
  if (m.cm.fn == 0 && m.cm.en > 0)
    throw InputError(qUtf8Printable(
        QString("the current layer \"%1\" holds curves (%2 edges), not a surface: select the scanned mesh layer "
                "(View > Show Layer Dialog) and run the filter again.")
            .arg(m.label())
            .arg(thousands(m.cm.en))));
  View v = from_vcg(m.cm);
  require_triangles(v.mesh);
  repair_view(v);
  const std::string said = v.repair.summary();
  if (!said.empty() && log) log(QString::fromStdString(said));
  return v;
}

Surface surface_of(View& view) { return Surface::borrow(view.mesh, std::move(view.faces)); }

void write_vertex_attribute(CMeshO& m, const View& v, const char* name, const std::vector<double>& values) {
  auto h = vcg::tri::Allocator<CMeshO>::GetPerVertexAttribute<Scalarm>(m, std::string(name));
  const int n = static_cast<int>(values.size());
  for_each_vertex(v, [&](int i, CVertexO* p) {
    if (i < n) h[p] = Scalarm(values[i]);
  });
}

MeshModel* add_curve_layer(MeshDocument& doc, const QString& label, const Polylines& curves, vcg::Color4b color,
                           const std::vector<Vec3>* normals, double lift) {
  MeshModel* layer = doc.addNewMesh("", label, false);
  CMeshO& cm = layer->cm;
  layer->updateDataMask(MeshModel::MM_VERTCOLOR | MeshModel::MM_VERTQUALITY);
  const bool lifted = normals != nullptr && lift > 0 && curves.point_edge.size() == curves.points.size();
  if (!curves.points.empty()) {
    auto vi = vcg::tri::Allocator<CMeshO>::AddVertices(cm, curves.points.size());
    for (size_t i = 0; i < curves.points.size(); ++i, ++vi) {
      Vec3 p = curves.points[i];
      if (lifted) {
        const auto& e = curves.point_edge[i];
        const double w = curves.point_weight[i];
        Vec3 n = (1 - w) * (*normals)[e[0]] + w * (*normals)[e[1]];
        if (n.norm() > 0) p += lift * n.normalized();
      }
      vi->P() = Point3m(Scalarm(p.x()), Scalarm(p.y()), Scalarm(p.z()));
      vi->Q() = float(curves.strength[i]);
      vi->C() = color;
    }
    auto ei = vcg::tri::Allocator<CMeshO>::AddEdges(cm, curves.segments.size());
    for (size_t k = 0; k < curves.segments.size(); ++k, ++ei) {
      ei->V(0) = &cm.vert[curves.segments[k][0]];
      ei->V(1) = &cm.vert[curves.segments[k][1]];
    }
  }
  vcg::tri::UpdateBounding<CMeshO>::Box(cm);
  return layer;
}

MeshModel* add_mesh_layer(MeshDocument& doc, const QString& label, const TriMesh& mesh, const std::vector<double>& quality,
                          const std::vector<std::pair<const char*, const std::vector<double>*>>& attributes, bool current) {
  MeshModel* layer = doc.addNewMesh("", label, current);
  CMeshO& cm = layer->cm;
  layer->updateDataMask(MeshModel::MM_VERTQUALITY);
  if (mesh.n_vertices() > 0) {
    auto vi = vcg::tri::Allocator<CMeshO>::AddVertices(cm, size_t(mesh.n_vertices()));
    for (int v = 0; v < mesh.n_vertices(); ++v, ++vi) {
      const Vec3& p = mesh.vertices[v];
      vi->P() = Point3m(Scalarm(p.x()), Scalarm(p.y()), Scalarm(p.z()));
      vi->Q() = Scalarm(v < int(quality.size()) ? quality[size_t(v)] : 0);
    }
    auto fi = vcg::tri::Allocator<CMeshO>::AddFaces(cm, mesh.faces.size());
    for (size_t f = 0; f < mesh.faces.size(); ++f, ++fi)
      for (int k = 0; k < 3; ++k) fi->V(k) = &cm.vert[size_t(mesh.faces[f][size_t(k)])];
    for (const auto& [name, values] : attributes) {
      auto h = vcg::tri::Allocator<CMeshO>::GetPerVertexAttribute<float>(cm, name);
      for (size_t v = 0; v < cm.vert.size(); ++v) h[v] = v < values->size() ? float((*values)[v]) : 0.f;
    }
  }
  vcg::tri::UpdateBounding<CMeshO>::Box(cm);
  vcg::tri::UpdateNormal<CMeshO>::PerVertexNormalizedPerFaceNormalized(cm);
  return layer;
}

MeshModel* add_surface_layer(MeshDocument& doc, const QString& label, MeshModel& source, const View& view,
                             const std::vector<Vec3>& positions, const std::vector<double>* quality) {
  MeshModel* layer = doc.addNewMesh("", label, false);
  layer->updateDataMask(&source);
  if (quality) layer->updateDataMask(MeshModel::MM_VERTQUALITY);
  // MeshCopy keeps the live vertices in order: a source vertex's index in the copy is the number
  // of live vertices before it.
  std::vector<int> copy_index(source.cm.vert.size(), -1);
  int live = 0;
  for (size_t i = 0; i < source.cm.vert.size(); ++i)
    if (!source.cm.vert[i].IsD()) copy_index[i] = live++;
  vcg::tri::Append<CMeshO, CMeshO>::MeshCopy(layer->cm, source.cm);
  for_each_vertex(view, [&](int i, CVertexO* v) {
    const int k = copy_index[size_t(v - &source.cm.vert[0])];
    if (k < 0 || k >= int(layer->cm.vert.size())) return;
    const Vec3& p = positions[size_t(i)];
    layer->cm.vert[size_t(k)].P() = Point3m(Scalarm(p.x()), Scalarm(p.y()), Scalarm(p.z()));
    if (quality) layer->cm.vert[size_t(k)].Q() = Scalarm((*quality)[size_t(i)]);
  });
  vcg::tri::UpdateNormal<CMeshO>::PerVertexNormalizedPerFaceNormalized(layer->cm);
  vcg::tri::UpdateBounding<CMeshO>::Box(layer->cm);
  return layer;
}

void write_grey(MeshModel& m, const View& view, const std::vector<double>& grey, const std::vector<double>& quality) {
  m.updateDataMask(MeshModel::MM_VERTCOLOR | MeshModel::MM_VERTQUALITY);
  for_each_vertex(view, [&](int i, CVertexO* v) {
    const auto g = static_cast<unsigned char>(std::lround(255 * std::clamp(grey[size_t(i)], 0.0, 1.0)));
    v->C() = vcg::Color4b(g, g, g, 255);
    v->Q() = Scalarm(quality[size_t(i)]);
  });
}

Polylines curves_of_layer(const MeshModel& m) {
  Polylines c;
  const bool strength = m.hasDataMask(MeshModel::MM_VERTQUALITY);
  std::vector<int> index(size_t(m.cm.vert.size()), -1);
  for (size_t i = 0; i < m.cm.vert.size(); ++i)
    if (!m.cm.vert[i].IsD()) {
      const auto& q = m.cm.vert[i].cP();
      index[i] = int(c.points.size());
      c.points.push_back(Vec3(q[0], q[1], q[2]));
      if (strength) c.strength.push_back(m.cm.vert[i].cQ());
    }
  for (const auto& e : m.cm.edge)
    if (!e.IsD()) c.segments.push_back({index[size_t(vcg::tri::Index(m.cm, e.cV(0)))], index[size_t(vcg::tri::Index(m.cm, e.cV(1)))]});
  return c;
}

QString derived_label(const MeshModel& m, const QString& what) {
  QString name = m.label();
  int dot = name.lastIndexOf('.');
  if (dot > 0) name = name.left(dot);
  return name + QString::fromUtf8(" \u2013 ") + what;
}

void write_vertex_vectors(CMeshO& m, const View& v, const char* name, const std::vector<Vec3>& values) {
  auto h = vcg::tri::Allocator<CMeshO>::GetPerVertexAttribute<Point3m>(m, std::string(name));
  const int n = static_cast<int>(values.size());
  for_each_vertex(v, [&](int i, CVertexO* p) {
    if (i < n) h[p] = Point3m(Scalarm(values[i].x()), Scalarm(values[i].y()), Scalarm(values[i].z()));
  });
}

QString thousands(long long n) {
  QString s = QString::number(n < 0 ? -n : n);
  for (int i = s.size() - 3; i > 0; i -= 3) s.insert(i, ',');
  return n < 0 ? "-" + s : s;
}

namespace {
constexpr const char* kSheetMarks = "reliefkit_rollout_marks";
}

void set_sheet_marks(MeshModel& m, const SheetMarks& marks) {
  auto h = vcg::tri::Allocator<CMeshO>::GetPerMeshAttribute<SheetMarks>(m.cm, kSheetMarks);
  h() = marks;
}

std::optional<SheetMarks> sheet_marks_of(MeshModel& m) {
  auto h = vcg::tri::Allocator<CMeshO>::FindPerMeshAttribute<SheetMarks>(m.cm, kSheetMarks);
  if (!vcg::tri::Allocator<CMeshO>::IsValidHandle(m.cm, h)) return std::nullopt;
  return h();
}

}  // namespace reliefkit::ml
