// ReliefKit — MeshLab 2022.02's headers, for the adapter's other files (mesh bridge, parameters):
// the mesh and document types, the parameter list, and the plugin interface under one name (the
// twin of common/meshlab/meshlab_api.h).
#pragma once

#include <vector>

#include <common/ml_document/mesh_document.h>
#include <common/ml_document/mesh_model.h>
#include <common/parameters/rich_parameter_list.h>
#include <common/plugins/interfaces/filter_plugin.h>

namespace reliefkit::ml {
/// The plugin interface of this MeshLab (its FilterClass values name the filters' menus).
using FilterInterface = FilterPlugin;
using RichDirection = ::RichDirection;  // a direction parameter (MeshLab 2020.09: RichPoint3f)
/// The document's layers in order.
inline std::vector<MeshModel*> document_layers(MeshDocument& doc) {
  std::vector<MeshModel*> all;
  for (MeshModel& m : doc.meshIterator()) all.push_back(&m);
  return all;
}
}  // namespace reliefkit::ml
