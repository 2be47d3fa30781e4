// "Line Drawing to Curves", "Relief from Line Drawing", "Base from Drawing Silhouette", "Vessel from Profile
// Drawing": MeshLab adapters of reliefkit/drawing/line_drawing.h, drawing_interpretation.h, drawing_relief.h,
// drawing_file.h, base_library.h and vessel_profile.h.
#pragma once

#include "rk_plugin.h"

namespace reliefkit::ml {
FilterSpec drawing_curves_filter(int id);
FilterSpec drawing_relief_filter(int id);
FilterSpec base_from_silhouette_filter(int id);  // base_filter.cpp
FilterSpec vessel_from_profile_filter(int id);   // vessel_filter.cpp
}  // namespace reliefkit::ml
