// "Relief Edges", "Estimate Base Normals", "Ridges and Valleys": MeshLab adapters of core/.
#pragma once

#include "rk_plugin.h"

namespace reliefkit::ml {
FilterSpec relief_edges_filter(int id);
FilterSpec base_normals_filter(int id);
FilterSpec ridges_valleys_filter(int id);
}  // namespace reliefkit::ml
