// ReliefKit — moving data between MeshLab's CMeshO and the cores (MeshLab 2020.09 types).
#pragma once

#include <common/meshmodel.h>

#include <QString>
#include <vector>

#include "reliefkit/mesh.h"
#include "reliefkit/vcg_adapter.h"

namespace reliefkit::ml {

using View = VcgView<CMeshO>;

/// Copies the layer's live vertices and faces. Throws InputError if the layer has no faces or
/// invalid coordinates (require_triangles).
View view_of(MeshModel& m);

/// Writes a named per-vertex float attribute (created if missing, overwritten if present).
/// Vertices not in the view keep their old value.
void write_vertex_attribute(CMeshO& m, const View& v, const char* name, const std::vector<double>& values);

/// Mean edge length of the layer (for parameter defaults), or a fraction of the bounding box
/// diagonal when the layer has no faces.
double mean_edge_length(MeshModel& m);

/// "12,345" — numbers in log lines.
QString thousands(long long n);

}  // namespace reliefkit::ml
