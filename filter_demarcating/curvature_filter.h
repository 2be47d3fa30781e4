// "Compute Curvature Tensor and Derivatives": MeshLab adapter of reliefkit::compute_curvature.
#pragma once

#include "rk_plugin.h"

namespace reliefkit::ml {
FilterSpec curvature_tensor_filter(int id);
}
