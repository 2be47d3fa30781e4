#include "server.h"

#include "mesh_files.h"

#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace rktest {

static std::string quote(const std::string& s) {
  std::string r = "'";
  for (char c : s) r += (c == '\'') ? std::string("'\\''") : std::string(1, c);
  return r + "'";
}

std::string source_dir() { return RELIEFKIT_SOURCE_DIR; }
std::string binary_dir() { return RELIEFKIT_BINARY_DIR; }

ServerRun run_meshlabserver(const std::vector<std::string>& args) {
  std::string cmd = quote(source_dir() + "/scripts/meshlabserver");
  for (const auto& a : args) cmd += " " + quote(a);
  cmd += " 2>&1";
  ServerRun r;
  FILE* p = popen(cmd.c_str(), "r");
  if (!p) return r;
  std::array<char, 4096> buf;
  size_t n;
  while ((n = fread(buf.data(), 1, buf.size(), p)) > 0) r.output.append(buf.data(), n);
  int st = pclose(p);
  if (WIFSIGNALED(st)) {
    r.crashed = true;
  } else if (WIFEXITED(st)) {
    r.status = WEXITSTATUS(st);
    // xvfb-run reports a child killed by signal N as 128 + N; meshlabserver's exit(-1) is 255.
    r.crashed = r.status > 128 && r.status < 160;
  }
  return r;
}

std::string temp_dir(const std::string& name) {
  auto d = std::filesystem::path(binary_dir()) / "test-output" / name;
  std::filesystem::remove_all(d);
  std::filesystem::create_directories(d);
  return d.string();
}

std::string mlx_filter(const std::string& name, const std::vector<std::string>& params) {
  std::string s = " <filter name=\"" + name + "\">\n";
  for (const auto& p : params) s += "  " + p + "\n";
  return s + " </filter>\n";
}

std::string param_file(const std::string& name, const std::string& path) {
  return "<Param type=\"RichOpenFile\" name=\"" + name + "\" value=\"" + path + "\" exts_cardinality=\"0\"/>";
}

std::string param_save_file(const std::string& name, const std::string& path, const std::string& ext) {
  return "<Param type=\"RichSaveFile\" name=\"" + name + "\" value=\"" + path + "\" ext=\"" + ext + "\"/>";
}

std::string param_point(const std::string& name, double x, double y, double z) {
  std::ostringstream s;
  s << "<Param type=\"RichPoint3f\" name=\"" << name << "\" x=\"" << x << "\" y=\"" << y << "\" z=\"" << z << "\"/>";
  return s.str();
}

std::string mlx_script(const std::vector<std::string>& filters) {
  std::string s = "<!DOCTYPE FilterScript>\n<FilterScript>\n";
  for (const auto& f : filters) s += f;
  return s + "</FilterScript>\n";
}

std::string param_enum(const std::string& name, int value, int cardinality) {
  std::ostringstream s;
  s << "<Param type=\"RichEnum\" name=\"" << name << "\" value=\"" << value << "\" enum_cardinality=\""
    << cardinality << "\"";
  for (int i = 0; i < cardinality; ++i) s << " enum_val" << i << "=\"" << i << "\"";
  s << "/>";
  return s.str();
}
std::string param_string(const std::string& name, const std::string& value) {
  return "<Param type=\"RichString\" name=\"" + name + "\" value=\"" + value + "\"/>";
}

std::string param_absperc(const std::string& name, double value) {
  std::ostringstream s;
  s << "<Param type=\"RichAbsPerc\" name=\"" << name << "\" value=\"" << value << "\" min=\"0\" max=\"1e9\"/>";
  return s.str();
}
std::string param_float(const std::string& name, double value) {
  std::ostringstream s;
  s << "<Param type=\"RichFloat\" name=\"" << name << "\" value=\"" << value << "\"/>";
  return s.str();
}
std::string param_int(const std::string& name, int value) {
  return "<Param type=\"RichInt\" name=\"" + name + "\" value=\"" + std::to_string(value) + "\"/>";
}

std::string param_bool(const std::string& name, bool value) {
  return "<Param type=\"RichBool\" name=\"" + name + "\" value=\"" + (value ? "true" : "false") + "\"/>";
}

void write_text(const std::string& path, const std::string& text) { std::ofstream(path) << text; }

ServerRun run_filters(const std::string& name, const reliefkit::TriMesh& mesh, const std::vector<std::string>& filters,
                      std::vector<std::string> outputs, std::string* dir_out) {
  const std::string dir = temp_dir(name);
  write_ply(dir + "/in.ply", mesh);
  write_text(dir + "/s.mlx", mlx_script(filters));
  for (size_t i = 0; i + 1 < outputs.size(); ++i)
    if (outputs[i] == "-o") outputs[i + 1] = dir + "/" + outputs[i + 1];
  std::vector<std::string> args{"-i", dir + "/in.ply"};
  args.insert(args.end(), outputs.begin(), outputs.end());
  args.push_back("-s");
  args.push_back(dir + "/s.mlx");
  if (dir_out) *dir_out = dir;
  return run_meshlabserver(args);
}

}  // namespace rktest
