// ReliefKit — Prominent plugin (thesis chapter 6): the prominent field, enhancement and coloring.
#pragma once

#include "rk_plugin.h"

class ReliefKitProminentPlugin : public reliefkit::ml::ReliefKitPlugin {
  Q_OBJECT
  MESHLAB_PLUGIN_IID_EXPORTER(MESH_FILTER_INTERFACE_IID)
  Q_INTERFACES(MeshFilterInterface)
 public:
  ReliefKitProminentPlugin();
};
