// ReliefKit — Prominent plugin (thesis chapter 6): the prominent field, enhancement and coloring.
#pragma once

#include "rk_plugin.h"

class ReliefKitProminentPlugin : public reliefkit::ml::ReliefKitPlugin {
  Q_OBJECT
  RELIEFKIT_FILTER_PLUGIN
 public:
  ReliefKitProminentPlugin();
};
