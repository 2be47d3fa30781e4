// "Line Drawing to Curves", "Relief from Line Drawing": MeshLab adapters of reliefkit/line_drawing.h,
// drawing_interpretation.h, drawing_relief.h and drawing_file.h.
#pragma once

#include "rk_plugin.h"

namespace reliefkit::ml {
FilterSpec drawing_curves_filter(int id);
FilterSpec drawing_relief_filter(int id);
}  // namespace reliefkit::ml
