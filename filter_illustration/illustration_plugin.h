// ReliefKit — Illustration plugin: the illustrator's plate of a scan and its curves.
#pragma once

#include "rk_plugin.h"

class ReliefKitIllustrationPlugin : public reliefkit::ml::ReliefKitPlugin {
  Q_OBJECT
  RELIEFKIT_FILTER_PLUGIN
 public:
  ReliefKitIllustrationPlugin();
};
