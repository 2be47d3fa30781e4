// ReliefKit — MeshLab 2020.09's headers, for the adapter's other files (mesh bridge, parameters):
// the mesh and document types, the parameter list, and the plugin interface under one name. Its
// twin for MeshLab 2022.02 and 2025.07 is common/meshlab_filterplugin/meshlab_api.h (RELIEFKIT_MESHLAB_API chooses).
#pragma once

#include <vector>

#include <common/interfaces.h>
#include <common/meshmodel.h>

namespace reliefkit::ml {
/// The plugin interface of this MeshLab (its FilterClass values name the filters' menus).
using FilterInterface = MeshFilterInterface;
using RichDirection = ::RichPoint3f;  // a direction parameter (MeshLab 2022.02: RichDirection)
using RichPosition = ::RichPoint3f;   // a point parameter (MeshLab 2022.02: RichPosition)
using RichOpenFile = ::RichOpenFile;   // file parameters (MeshLab 2025.07: RichFileOpen, RichFileSave)
using RichSaveFile = ::RichSaveFile;
using Point3Value = ::Point3fValue;    // the point value (MeshLab 2025.07: Point3Value)
inline bool is_point3(const Value& v) { return v.isPoint3f(); }
inline Point3m point3_of(const Value& v) { return v.getPoint3f(); }
/// The document's layers in order.
inline std::vector<MeshModel*> document_layers(MeshDocument& doc) { return {doc.meshList.begin(), doc.meshList.end()}; }
}  // namespace reliefkit::ml
