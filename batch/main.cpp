// reliefkit-batch — MeshLab filter scripts (ours and MeshLab's own filters) over a file or a whole
// folder tree of scans or drawings, headless, without meshlabserver:
//
//   reliefkit-batch --script curves.mlx scans/ out/            # every scan under scans/
//   reliefkit-batch --filter "Demarcating Curves" -p "Curvature threshold=0.2" coin.ply out/
//   reliefkit-batch merge out/                                 # summary.csv / .json of all shards
//
// Each file is handled in a process of its own; results are kept per file under
// out/.reliefkit-batch/results, so a run started again skips what is done. See docs/batch.md.
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

#include "collection.h"
#include "results.h"
#include "supervisor.h"
#include "worker.h"

extern char** environ;
namespace fs = std::filesystem;
using namespace reliefkit::batch;

namespace {

constexpr const char* kUsage =
    "usage: reliefkit-batch [options] INPUT OUTPUT   (INPUT: a file or a folder, searched recursively)\n"
    "       reliefkit-batch merge OUTPUT             (the summary of every shard's results in OUTPUT)\n"
    "       reliefkit-batch --list-filters\n"
    "what to apply (one of):\n"
    "  -s, --script FILE.mlx        a MeshLab filter script (parameters it omits: the defaults)\n"
    "  -f, --filter NAME            one filter by its exact name, with\n"
    "  -p, --param NAME=VALUE       its parameters by name (repeat; the rest at their defaults);\n"
    "                               {input} in a text value is the file's path\n"
    "options:\n"
    "  -j, --jobs N                 files handled at once (default 1); each job's filters use cores / N threads\n"
    "                               (OMP_NUM_THREADS, when not set) and wait passively (OMP_WAIT_POLICY)\n"
    "  --memory-cap SIZE            memory of all jobs together, e.g. 16G or 900M (default 90 % of the machine's);\n"
    "                               a job over cap / jobs is stopped and recorded as \"memory\"\n"
    "  --shard i/N                  process shard i of N (default: the Slurm job array's task, else all)\n"
    "  --save all|new|current|none  layers written per file (default all); curves always as OBJ\n"
    "  --format ply|obj|off|stl     format of layers with faces (default ply)\n"
    "  --extensions LIST            files taken from a folder (default ply,obj,off,stl; drawings: png,jpg,tif)\n"
    "  --retry-failed               process again the files that failed or crashed (done ones are skipped)\n"
    "  --plugins DIR                MeshLab's plugin folder (default: the installed MeshLab's)\n"
    "exit status: 0 all files ok, 1 some failed, crashed or ran out of memory, 2 a usage error\n";

struct Options {
  std::string input, output, plugins;
  Recipe recipe;
  SaveChoice save;
  int jobs = 1;
  long memory_cap_mib = 0;
  Shard shard;
  bool shard_given = false, retry_failed = false, list = false, worker = false;
  std::vector<std::string> extensions{"ply", "obj", "off", "stl"};
  std::vector<std::string> positional;
};

long parse_size_mib(const std::string& text) {
  char* end = nullptr;
  const double v = std::strtod(text.c_str(), &end);
  const std::string unit = end ? end : "";
  const double mib = unit == "G" || unit == "g" ? v * 1024 : unit == "M" || unit == "m" || unit.empty() ? v : -1;
  if (!(mib > 0)) throw std::invalid_argument("--memory-cap is a size such as 16G or 900M, not \"" + text + "\"");
  return long(mib);
}

std::vector<std::string> split_list(const std::string& text) {
  std::vector<std::string> parts;
  size_t start = 0;
  while (start <= text.size()) {
    const size_t comma = text.find(',', start);
    const std::string p = text.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
    if (!p.empty()) parts.push_back(p);
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  return parts;
}

void set_choice(std::string& target, const std::string& value, const std::vector<std::string>& allowed, const char* what) {
  for (const auto& a : allowed)
    if (a == value) { target = value; return; }
  throw std::invalid_argument(std::string(what) + " is one of " + [&] { std::string s; for (auto& a : allowed) s += (s.empty() ? "" : ", ") + a; return s; }() + ", not \"" + value + "\"");
}

// One option (and its value) at argv[i]; false when argv[i] is not an option.
bool read_option(Options& o, int argc, char** argv, int& i) {
  const std::string a = argv[i];
  auto value = [&]() -> std::string {
    if (i + 1 >= argc) throw std::invalid_argument(a + " needs a value");
    return argv[++i];
  };
  if (a == "-s" || a == "--script") o.recipe.script = value();
  else if (a == "-f" || a == "--filter") o.recipe.filter = value();
  else if (a == "-p" || a == "--param") {
    const std::string p = value();
    const size_t eq = p.find('=');
    if (eq == std::string::npos || eq == 0) throw std::invalid_argument("--param is NAME=VALUE, not \"" + p + "\"");
    o.recipe.parameters.push_back({p.substr(0, eq), p.substr(eq + 1)});
  } else if (a == "-j" || a == "--jobs") {
    o.jobs = std::atoi(value().c_str());
    if (o.jobs < 1 || o.jobs > 256) throw std::invalid_argument("--jobs is a number from 1 to 256");
  } else if (a == "--memory-cap") o.memory_cap_mib = parse_size_mib(value());
  else if (a == "--shard") { o.shard = parse_shard(value()); o.shard_given = true; }
  else if (a == "--save") set_choice(o.save.layers, value(), {"all", "new", "current", "none"}, "--save");
  else if (a == "--format") set_choice(o.save.mesh_format, value(), {"ply", "obj", "off", "stl"}, "--format");
  else if (a == "--extensions") o.extensions = split_list(value());
  else if (a == "--retry-failed") o.retry_failed = true;
  else if (a == "--plugins") o.plugins = value();
  else if (a == "--list-filters") o.list = true;
  else if (a == "--worker") o.worker = true;
  else if (a == "-h" || a == "--help") { std::fputs(kUsage, stdout); std::exit(0); }
  else if (a.size() > 1 && a[0] == '-') throw std::invalid_argument("unknown option " + a);
  else return false;
  return true;
}

Options parse(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i)
    if (!read_option(o, argc, argv, i)) o.positional.push_back(argv[i]);
  if (o.list || o.worker) return o;
  if (o.positional.size() != 2) throw std::invalid_argument("give an INPUT and an OUTPUT folder");
  if (o.recipe.script.empty() == o.recipe.filter.empty()) throw std::invalid_argument("give one of --script and --filter");
  if (!o.recipe.script.empty() && !o.recipe.parameters.empty()) throw std::invalid_argument("--param goes with --filter; a script holds its parameters");
  o.input = o.positional[0];
  o.output = o.positional[1];
  return o;
}

std::map<std::string, std::string> environment() {
  std::map<std::string, std::string> env;
  for (char** e = environ; *e; ++e) {
    const std::string kv = *e;
    const size_t eq = kv.find('=');
    if (eq != std::string::npos) env[kv.substr(0, eq)] = kv.substr(eq + 1);
  }
  return env;
}

std::string self_path() {
  std::error_code ec;
  const fs::path p = fs::read_symlink("/proc/self/exe", ec);
  return ec ? std::string("reliefkit-batch") : p.string();
}

// The worker's command line: this program with the recipe and where things go (file appended).
std::vector<std::string> worker_command(const Options& o, const std::string& shard) {
  std::vector<std::string> c{self_path(), "--worker", "--plugins", o.plugins, "--save", o.save.layers, "--format", o.save.mesh_format,
                             "--shard", shard};
  if (!o.recipe.script.empty()) c.insert(c.end(), {"--script", fs::absolute(o.recipe.script).string()});
  else c.insert(c.end(), {"--filter", o.recipe.filter});
  for (const auto& [name, value] : o.recipe.parameters) c.insert(c.end(), {"--param", name + "=" + value});
  c.push_back(fs::absolute(o.output).string());  // the worker's OUTPUT; FILE and RELATIVE follow
  return c;
}

int run_worker(const Options& o) {
  // positional: OUTPUT FILE RELATIVE
  if (o.positional.size() != 3) throw std::invalid_argument("--worker takes OUTPUT FILE RELATIVE");
  const WorkerRequest request{o.positional[1], o.positional[2], o.positional[0],
                              std::to_string(o.shard.index) + "/" + std::to_string(o.shard.count), o.plugins, o.recipe, o.save};
  const FileResult r = process_file(request);
  write_result(result_path(request.output, request.relative), r);
  return 0;
}

int run_collection(Options& o) {
  if (!o.shard_given) shard_from_slurm(environment(), o.shard);
  const std::string shard = std::to_string(o.shard.index) + "/" + std::to_string(o.shard.count);
  const std::vector<std::string> all = list_collection(o.input, o.extensions);
  const std::vector<std::string> mine = shard_of(all, o.shard);
  std::vector<Job> todo;
  std::vector<std::string> relatives;
  for (const auto& f : mine) {
    const std::string rel = relative_to_input(o.input, f);
    relatives.push_back(rel);
    if (is_done(o.output, rel, o.retry_failed)) continue;
    fs::remove(result_path(o.output, rel));
    todo.push_back({fs::absolute(f).string(), rel});
  }
  const char* threads = std::getenv("OMP_NUM_THREADS");
  std::printf("reliefkit-batch: %zu files in %s; shard %s: %zu, %zu done before, %zu to do, %d at a time, %s threads each\n",
              all.size(), o.input.c_str(), shard.c_str(), mine.size(), mine.size() - todo.size(), todo.size(), o.jobs,
              threads ? threads : std::to_string(threads_per_job(usable_cores(), o.jobs)).c_str());
  std::fflush(stdout);
  RunOptions ro{o.jobs, o.memory_cap_mib > 0 ? o.memory_cap_mib : machine_memory_mib() * 9 / 10, worker_command(o, shard),
                o.output, shard};
  run_jobs(todo, ro, [](const std::string& line) { std::printf("%s\n", line.c_str()); std::fflush(stdout); });
  std::vector<FileResult> results;
  for (const auto& rel : relatives) {
    FileResult r;
    if (read_result(result_path(o.output, rel), r)) results.push_back(r);
  }
  const std::string base = (fs::path(o.output) / (o.shard.count > 1 ? "summary-shard-" + std::to_string(o.shard.index) + "-of-" +
                                                                           std::to_string(o.shard.count) : "summary")).string();
  write_summary(base, results);
  std::printf("reliefkit-batch: shard %s: %zu files: %s; summary %s.csv\n", shard.c_str(), results.size(),
              status_counts(results).c_str(), base.c_str());
  for (const auto& r : results)
    if (r.status != "ok") return 1;
  return 0;
}

int merge(const std::vector<std::string>& outputs) {
  int status = 0;
  for (const auto& out : outputs) {
    const std::vector<FileResult> results = all_results(out);
    if (results.empty()) throw std::invalid_argument("no results in " + out + " (a reliefkit-batch output folder?)");
    write_summary((fs::path(out) / "summary").string(), results);
    std::printf("reliefkit-batch merge: %s: %zu files: %s; summary %s/summary.csv\n", out.c_str(), results.size(),
                status_counts(results).c_str(), out.c_str());
    for (const auto& r : results)
      if (r.status != "ok") status = 1;
  }
  return status;
}
}  // namespace

int main(int argc, char** argv) {
  try {
    if (argc >= 2 && std::string(argv[1]) == "merge") {
      if (argc < 3) throw std::invalid_argument("merge needs the OUTPUT folder(s)");
      return merge(std::vector<std::string>(argv + 2, argv + argc));
    }
    Options o = parse(argc, argv);
    if (o.plugins.empty()) o.plugins = default_plugin_folder();
    if (o.list) { std::fputs(list_filters(o.plugins).c_str(), stdout); return 0; }
    return o.worker ? run_worker(o) : run_collection(o);
  } catch (const std::invalid_argument& e) {
    std::fprintf(stderr, "reliefkit-batch: %s\n\n%s", e.what(), kUsage);
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "reliefkit-batch: %s\n", e.what());
    return 2;
  }
}
