// ReliefKit — Relief edges plugin (thesis chapter 4): relief edges, base normals, ridges & valleys.
#pragma once

#include "rk_plugin.h"

class ReliefKitReliefEdgesPlugin : public reliefkit::ml::ReliefKitPlugin {
  Q_OBJECT
  MESHLAB_PLUGIN_IID_EXPORTER(MESH_FILTER_INTERFACE_IID)
  Q_INTERFACES(MeshFilterInterface)
 public:
  ReliefKitReliefEdgesPlugin();
};
