// ReliefKit — Demarcating curves plugin (thesis chapter 3): curvature tensor, demarcating curves.
#pragma once

#include "rk_plugin.h"

class ReliefKitDemarcatingPlugin : public reliefkit::ml::ReliefKitPlugin {
  Q_OBJECT
  RELIEFKIT_FILTER_PLUGIN
 public:
  ReliefKitDemarcatingPlugin();
};
