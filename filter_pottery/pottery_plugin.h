// ReliefKit — Pottery plugin (issue 42): vessels and sherds from their scans.
#pragma once

#include "rk_plugin.h"

class ReliefKitPotteryPlugin : public reliefkit::ml::ReliefKitPlugin {
  Q_OBJECT
  RELIEFKIT_FILTER_PLUGIN
 public:
  ReliefKitPotteryPlugin();
};
