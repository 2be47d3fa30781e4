// "Vessel Axis and Profile": MeshLab adapter of reliefkit/pottery/vessel_record.h.
#pragma once

#include "rk_plugin.h"

namespace reliefkit::ml {
FilterSpec vessel_axis_filter(int id);  // vessel_axis_filter.cpp
}  // namespace reliefkit::ml
