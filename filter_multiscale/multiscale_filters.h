// "Compute Optimal Scale", "Optimally Smoothed Surface", "Multi-scale Ridges and Valleys",
// "Multi-scale Relief Edges": MeshLab adapters of reliefkit/multiscale/optimal_scale.h and multiscale.h.
#pragma once

#include "rk_plugin.h"

namespace reliefkit::ml {
FilterSpec optimal_scale_filter(int id);
FilterSpec smoothed_surface_filter(int id);
FilterSpec multiscale_ridges_filter(int id);
FilterSpec multiscale_relief_edges_filter(int id);
}  // namespace reliefkit::ml
