// "Unroll Around Axis": MeshLab adapter of reliefkit/rollout/unroll.h.
#pragma once

#include "rk_plugin.h"

namespace reliefkit::ml {
FilterSpec unroll_filter(int id);  // unroll_filter.cpp
}  // namespace reliefkit::ml
