// ReliefKit — Drawing plugin (thesis chapter 7): curves of a raster line drawing, and a relief
// reconstructed from them.
#pragma once

#include "rk_plugin.h"

class ReliefKitDrawingPlugin : public reliefkit::ml::ReliefKitPlugin {
  Q_OBJECT
  RELIEFKIT_FILTER_PLUGIN
 public:
  ReliefKitDrawingPlugin();
};
