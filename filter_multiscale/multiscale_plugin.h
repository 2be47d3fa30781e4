// ReliefKit — Multi-scale plugin (thesis chapter 5): the optimal scale of every vertex, the
// optimally smoothed surface, multi-scale ridges & valleys and relief edges.
#pragma once

#include "rk_plugin.h"

class ReliefKitMultiscalePlugin : public reliefkit::ml::ReliefKitPlugin {
  Q_OBJECT
  RELIEFKIT_FILTER_PLUGIN
 public:
  ReliefKitMultiscalePlugin();
};
