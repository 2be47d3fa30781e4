// ReliefKit — moving data between MeshLab's CMeshO and the cores (MeshLab 2020.09 or 2022.02).
#pragma once

#include <meshlab_api.h>  // the MeshLab configured (RELIEFKIT_MESHLAB_API)

#include <QString>
#include <functional>
#include <optional>
#include <vector>

#include "reliefkit/base/mesh.h"
#include "reliefkit/base/surface.h"
#include "reliefkit/base/vcg_adapter.h"
#include "reliefkit/base/zero_crossings.h"

namespace reliefkit {
struct SheetMarks;  // reliefkit/rollout/unroll.h
}

namespace reliefkit::ml {

using View = VcgView<CMeshO>;

/// Copies the layer's live vertices and faces and repairs the copy for the computation
/// (repair_view: coincident vertices welded, duplicated faces dropped, orientation made coherent;
/// what was repaired goes to `log`). Throws InputError if the layer holds only curves, has no
/// faces or invalid coordinates (require_triangles).
View view_of(MeshModel& m, const std::function<void(const QString&)>& log);

/// The run's geometry context over the view's mesh (which must outlive it), with the adjacency the
/// repair built: the filter's cores share it, so that a run computes its topology, scale and noise once.
Surface surface_of(View& view);

/// Writes a named per-vertex float attribute (created if missing, overwritten if present).
/// Vertices not in the view keep their old value.
void write_vertex_attribute(CMeshO& m, const View& v, const char* name, const std::vector<double>& values);

/// Adds a new layer holding `curves` as an edge mesh: one vertex per curve point, one edge per
/// segment, vertex quality = point strength, vertices coloured `color`. With `normals` (per
/// vertex of the surface) and `lift` > 0 (mesh units) each point is lifted off the surface along
/// the interpolated normal, so that MeshLab draws the curves over the surface without flicker.
/// The layer is not made current, so later filters of a script still act on the surface.
MeshModel* add_curve_layer(MeshDocument& doc, const QString& label, const Polylines& curves,
                           vcg::Color4b color = vcg::Color4b(0, 0, 0, 255), const std::vector<Vec3>* normals = nullptr,
                           double lift = 0);

/// Adds a new layer: a copy of `source` (all its per-vertex data) whose vertices in `view` take
/// `positions` (per view vertex); normals recomputed; with `quality` (per view vertex), vertex quality
/// too. The layer is not made current.
MeshModel* add_surface_layer(MeshDocument& doc, const QString& label, MeshModel& source, const View& view,
                             const std::vector<Vec3>& positions, const std::vector<double>* quality = nullptr);

/// Adds a new layer holding `mesh` (normals computed), vertex quality = `quality` (per vertex) and
/// the named per-vertex float attributes. `current`: the new layer becomes the current one.
MeshModel* add_mesh_layer(MeshDocument& doc, const QString& label, const TriMesh& mesh, const std::vector<double>& quality,
                          const std::vector<std::pair<const char*, const std::vector<double>*>>& attributes, bool current);

/// A layer's live vertices and edges as curves: its points, their strength = vertex quality (empty
/// when the layer has none), its segments.
Polylines curves_of_layer(const MeshModel& m);

/// "<mesh name> – <what>": the label of a layer derived from `m` (file extension dropped).
QString derived_label(const MeshModel& m, const QString& what);

/// Grey vertex colours (grey in [0, 1] per view vertex, clamped) and vertex quality = `quality`.
void write_grey(MeshModel& m, const View& view, const std::vector<double>& grey, const std::vector<double>& quality);

/// Writes a named per-vertex Point3 attribute.
void write_vertex_vectors(CMeshO& m, const View& v, const char* name, const std::vector<Vec3>& values);

/// A rollout's marks (its seam, what the sheet is) kept on its layer for the filters that follow in
/// the same session (the plate): a per-mesh attribute, not saved with the mesh's file.
void set_sheet_marks(MeshModel& m, const SheetMarks& marks);
std::optional<SheetMarks> sheet_marks_of(MeshModel& m);

/// "12,345" — numbers in log lines.
QString thousands(long long n);

}  // namespace reliefkit::ml
