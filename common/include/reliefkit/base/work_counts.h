// ReliefKit — how often a process computed the things a run should compute once: the vertex-face
// adjacency, the mesh's scale, the noise estimate, the cotangent Laplacian, the noise-floor
// simulation, the repair check and the curvature (of any positions). Cheap (one relaxed atomic increment per computation), always on.
// The MeshLab adapter logs them after each filter when RELIEFKIT_WORK_COUNTS is set in the
// environment (scripts/work-counts.sh tabulates them); tests read them to hold a run to its budget.
#pragma once

#include <string>

namespace reliefkit {

enum class Work { Adjacency, MeshScale, Noise, Laplacian, NoiseFloor, Repair, Curvature, Count_ };

struct WorkCounts {
  long long n[static_cast<int>(Work::Count_)] = {};
  long long operator[](Work w) const { return n[static_cast<int>(w)]; }
  /// "adjacency 1, scale 1, noise 1, Laplacian 0, noise floor 1, repair 1, curvature 3"
  std::string summary() const;
};

/// Counts since the process started or since the last reset.
WorkCounts work_counts();
void reset_work_counts();
/// Called by the computation itself.
void count_work(Work w);

}  // namespace reliefkit
