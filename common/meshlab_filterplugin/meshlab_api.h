// ReliefKit — MeshLab 2022.02's and 2025.07's headers, for the adapter's other files (mesh bridge,
// parameters): the mesh and document types, the parameter list, and the plugin interface under one
// name, with the few names that differ between the releases (the twin of common/meshlab/meshlab_api.h).
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
using RichPosition = ::RichPosition;    // a point parameter (MeshLab 2020.09: RichPoint3f)
// File parameters and the point value: renamed in MeshLab 2023.12 (the names in .mlx scripts,
// "RichOpenFile" and "RichSaveFile", are the same in every release).
#if RELIEFKIT_MESHLAB_API >= 2025
using RichOpenFile = ::RichFileOpen;
using RichSaveFile = ::RichFileSave;
using Point3Value = ::Point3Value;
inline bool is_point3(const Value& v) { return v.isPoint3(); }
inline Point3m point3_of(const Value& v) { return v.getPoint3(); }
#else
using RichOpenFile = ::RichOpenFile;
using RichSaveFile = ::RichSaveFile;
using Point3Value = ::Point3fValue;
inline bool is_point3(const Value& v) { return v.isPoint3f(); }
inline Point3m point3_of(const Value& v) { return v.getPoint3f(); }
#endif
/// The document's layers in order.
inline std::vector<MeshModel*> document_layers(MeshDocument& doc) {
  std::vector<MeshModel*> all;
  for (MeshModel& m : doc.meshIterator()) all.push_back(&m);
  return all;
}
}  // namespace reliefkit::ml
