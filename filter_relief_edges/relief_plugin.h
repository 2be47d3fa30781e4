// ReliefKit — Relief edges plugin (thesis chapter 4): relief edges, base normals, ridges & valleys.
#pragma once

#include "rk_plugin.h"

class ReliefKitReliefEdgesPlugin : public reliefkit::ml::ReliefKitPlugin {
  Q_OBJECT
  RELIEFKIT_FILTER_PLUGIN
 public:
  ReliefKitReliefEdgesPlugin();
};
