// ReliefKit — Demarcating curves plugin (thesis chapter 3): curvature tensor, demarcating curves.
#pragma once

#include "rk_plugin.h"

class ReliefKitDemarcatingPlugin : public reliefkit::ml::ReliefKitPlugin {
  Q_OBJECT
  MESHLAB_PLUGIN_IID_EXPORTER(MESH_FILTER_INTERFACE_IID)
  Q_INTERFACES(MeshFilterInterface)
 public:
  ReliefKitDemarcatingPlugin();
};
