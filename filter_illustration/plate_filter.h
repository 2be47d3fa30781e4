// ReliefKit — "Export Illustration Plate": the current mesh and its curve layers as a plate for a
// report (SVG and PDF), over reliefkit/illustration/plate.h.
#pragma once

#include "rk_plugin.h"

namespace reliefkit::ml {
FilterSpec illustration_plate_filter(int id);
}  // namespace reliefkit::ml
