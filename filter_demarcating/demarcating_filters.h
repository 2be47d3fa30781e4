// "Demarcating Curves" and "Curvature Shading": MeshLab adapters of demarcating.h.
#pragma once

#include "rk_plugin.h"

namespace reliefkit::ml {
FilterSpec demarcating_curves_filter(int id);
FilterSpec curvature_shading_filter(int id);
}  // namespace reliefkit::ml
