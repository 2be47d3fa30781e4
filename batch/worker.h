// reliefkit-batch — one file through the filters, inside the installed MeshLab (its plugins,
// importers and exporters, loaded from its libmeshlab-common). The supervisor runs each file in a
// process of its own (this code), so that a file that crashes MeshLab stops that file only.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "results.h"

namespace reliefkit::batch {

/// What to apply: an .mlx filter script, or one filter by its exact name with name=value
/// parameters (the rest at their defaults). In a parameter's text value "{input}" stands for the
/// file's path (the drawing filters read their input from a parameter) and "{output}" for the
/// folder of its outputs (a plate: --param "file={output}/plate.svg").
struct Recipe {
  std::string script;
  std::string filter;
  std::vector<std::pair<std::string, std::string>> parameters;
};

/// Which layers are written after the filters: every layer ("all"), the layers the filters
/// added ("new"), the current layer ("current"), none. Layers with faces as `mesh_format` (ply,
/// obj, off, stl), layers of curves (edges, no faces) always as OBJ (MeshLab 2020.09's PLY writer
/// drops edges), points as PLY.
struct SaveChoice {
  std::string layers = "all";
  std::string mesh_format = "ply";
};

struct WorkerRequest {
  std::string file, relative, output, shard;
  std::string plugins;  // MeshLab's plugin folder (with ours)
  Recipe recipe;
  SaveChoice save;
};

/// Reads the file, applies the recipe, writes the layers and the file's result record. Progress
/// lines go to stdout. Never throws for the file's or the filters' faults: they end in a
/// "failed" record.
FileResult process_file(const WorkerRequest& request);

/// The filters the installed MeshLab and ours offer, with their parameters (for --list-filters).
std::string list_filters(const std::string& plugins);

/// The plugin folder MeshLab itself would use for this program: <binary dir>/../lib/<arch>/meshlab/plugins
/// when it exists, else the system MeshLab's.
std::string default_plugin_folder();

}  // namespace reliefkit::batch
