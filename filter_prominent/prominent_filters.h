// "Prominent Field", "Prominent Enhancement", "Prominent Coloring": MeshLab adapters of
// reliefkit/prominent/prominent.h.
#pragma once

#include "rk_plugin.h"

namespace reliefkit::ml {
FilterSpec prominent_field_filter(int id);
FilterSpec prominent_enhancement_filter(int id);
FilterSpec prominent_coloring_filter(int id);
}  // namespace reliefkit::ml
