// Running the real meshlabserver (private prefix with our plugins) from tests.
#pragma once

#include <string>
#include <vector>

#include "reliefkit/base/mesh.h"

namespace rktest {

struct ServerRun {
  int status = -1;       // exit status of the wrapper (xvfb-run passes meshlabserver's through)
  bool crashed = false;  // killed by a signal (abort, segfault): never acceptable
  std::string output;    // stdout + stderr
};

/// The source tree and the build tree (compiled into server.cpp alone, so that the other test
/// files do not depend on where the clone lies and a compiler cache serves every clone).
std::string source_dir();
std::string binary_dir();

/// Runs scripts/meshlabserver with the given arguments.
ServerRun run_meshlabserver(const std::vector<std::string>& args);

/// A temporary directory for one test (removed by the caller's choice; kept on failure).
std::string temp_dir(const std::string& name);

/// One <filter> element of an .mlx script; `params` are complete <Param .../> elements.
std::string mlx_filter(const std::string& name, const std::vector<std::string>& params);
std::string mlx_script(const std::vector<std::string>& filters);
std::string param_enum(const std::string& name, int value, int cardinality);
std::string param_absperc(const std::string& name, double value);
std::string param_float(const std::string& name, double value);
/// A length parameter as ReliefKit writes it: "auto" or a number of edge lengths.
std::string param_string(const std::string& name, const std::string& value);
std::string param_bool(const std::string& name, bool value);
std::string param_int(const std::string& name, int value);
/// A file name parameter (RichOpenFile), as MeshLab writes it.
std::string param_file(const std::string& name, const std::string& path);
/// A file to write (RichSaveFile), as MeshLab writes it.
std::string param_save_file(const std::string& name, const std::string& path, const std::string& ext);
std::string param_point(const std::string& name, double x, double y, double z);
void write_text(const std::string& path, const std::string& text);

/// Writes `mesh` as <dir>/in.ply and the filters as <dir>/s.mlx in a fresh test directory
/// `name`, runs meshlabserver on them with the output arguments (file names relative to the
/// directory, e.g. {"-o", "out.ply", "-m", "vq"}), and returns the run; `dir` receives the
/// directory.
ServerRun run_filters(const std::string& name, const reliefkit::TriMesh& mesh, const std::vector<std::string>& filters,
                      std::vector<std::string> outputs, std::string* dir = nullptr);

}  // namespace rktest
