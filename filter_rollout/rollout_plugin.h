// ReliefKit — Rollout plugin (issue 43): scans unrolled around an axis.
#pragma once

#include "rk_plugin.h"

class ReliefKitRolloutPlugin : public reliefkit::ml::ReliefKitPlugin {
  Q_OBJECT
  RELIEFKIT_FILTER_PLUGIN
 public:
  ReliefKitRolloutPlugin();
};
