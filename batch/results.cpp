// reliefkit-batch — result records and summaries. See results.h.
#include "results.h"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <stdexcept>

namespace fs = std::filesystem;
using nlohmann::json;

namespace reliefkit::batch {
namespace {

constexpr const char* kStatuses[] = {"ok", "failed", "crashed", "memory"};

json to_json(const FileResult& r) {
  json filters = json::array(), outputs = json::array();
  for (const auto& f : r.filters)
    filters.push_back({{"filter", f.filter}, {"seconds", f.seconds}, {"ok", f.ok}, {"parameters", f.parameters}});
  for (const auto& o : r.outputs)
    outputs.push_back({{"layer", o.layer}, {"file", o.file}, {"vertices", o.vertices}, {"faces", o.faces}, {"edges", o.edges}});
  return {{"file", r.file},         {"status", r.status},     {"seconds", r.seconds},
          {"vertices", r.vertices}, {"faces", r.faces},       {"peak_memory_mib", r.peak_memory_mib},
          {"filters", filters},     {"outputs", outputs},     {"warnings", r.warnings},
          {"error", r.error},       {"shard", r.shard},       {"record", r.record}};
}

FileResult from_json(const json& j) {
  FileResult r;
  r.file = j.at("file").get<std::string>();
  r.status = j.at("status").get<std::string>();
  r.seconds = j.value("seconds", 0.0);
  r.vertices = j.value("vertices", 0L);
  r.faces = j.value("faces", 0L);
  r.peak_memory_mib = j.value("peak_memory_mib", 0L);
  for (const auto& f : j.value("filters", json::array()))
    r.filters.push_back({f.value("filter", ""), f.value("seconds", 0.0), f.value("ok", false),
                         f.value("parameters", std::vector<std::string>{})});
  for (const auto& o : j.value("outputs", json::array()))
    r.outputs.push_back({o.value("layer", ""), o.value("file", ""), o.value("vertices", 0L), o.value("faces", 0L), o.value("edges", 0L)});
  r.warnings = j.value("warnings", std::vector<std::string>{});
  r.record = j.value("record", std::vector<std::string>{});
  r.error = j.value("error", "");
  r.shard = j.value("shard", "");
  return r;
}

std::string csv_field(const std::string& s) {
  if (s.find_first_of(",\"\n\r") == std::string::npos) return s;
  std::string q = "\"";
  for (char c : s) q += c == '"' ? std::string("\"\"") : std::string(1, c);
  return q + "\"";
}

std::string joined(const std::vector<std::string>& parts, const char* sep) {
  std::string s;
  for (const auto& p : parts) s += (s.empty() ? "" : sep) + p;
  return s;
}

void write_text(const std::string& path, const std::string& text) {
  const std::string tmp = path + ".part";
  {
    std::ofstream f(tmp, std::ios::binary | std::ios::trunc);
    if (!f) throw std::runtime_error("cannot write " + tmp);
    f << text;
    if (!f.flush()) throw std::runtime_error("cannot write " + tmp + " (disk full?)");
  }
  fs::rename(tmp, path);
}
}  // namespace

std::string result_path(const std::string& output, const std::string& relative) {
  return (fs::path(output) / ".reliefkit-batch" / "results" / (relative + ".json")).string();
}

bool read_result(const std::string& path, FileResult& result) {
  std::ifstream f(path);
  if (!f) return false;
  try {
    result = from_json(json::parse(f));
    return true;
  } catch (const std::exception&) {
    return false;  // a damaged record counts as none: the file is processed again
  }
}

void write_result(const std::string& path, const FileResult& result) {
  fs::create_directories(fs::path(path).parent_path());
  write_text(path, to_json(result).dump(1) + "\n");
}

bool is_done(const std::string& output, const std::string& relative, bool retry_failed) {
  FileResult r;
  if (!read_result(result_path(output, relative), r)) return false;
  return !retry_failed || r.status == "ok";
}

std::vector<FileResult> all_results(const std::string& output) {
  std::vector<FileResult> results;
  const fs::path dir = fs::path(output) / ".reliefkit-batch" / "results";
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) return results;
  for (const auto& e : fs::recursive_directory_iterator(dir, ec)) {
    FileResult r;
    if (e.is_regular_file() && e.path().extension() == ".json" && read_result(e.path().string(), r)) results.push_back(r);
  }
  std::sort(results.begin(), results.end(), [](const FileResult& a, const FileResult& b) { return a.file < b.file; });
  return results;
}

std::string status_counts(const std::vector<FileResult>& results) {
  std::string s;
  for (const char* status : kStatuses) {
    const long n = std::count_if(results.begin(), results.end(), [&](const FileResult& r) { return r.status == status; });
    s += (s.empty() ? "" : ", ") + std::to_string(n) + " " + status;
  }
  return s;
}

void write_summary(const std::string& base, const std::vector<FileResult>& results) {
  std::string csv = "file,status,seconds,vertices,faces,filters,outputs,warnings,error,record\n";
  json records = json::array();
  std::map<std::string, long> counts;
  for (const char* status : kStatuses) counts[status] = 0;
  for (const auto& r : results) {
    std::vector<std::string> filters, outputs;
    for (const auto& f : r.filters) filters.push_back(f.filter + (f.ok ? "" : " (failed)"));
    for (const auto& o : r.outputs) outputs.push_back(o.file);
    char seconds[32];
    std::snprintf(seconds, sizeof seconds, "%.2f", r.seconds);
    csv += csv_field(r.file) + "," + r.status + "," + seconds + "," + std::to_string(r.vertices) + "," +
           std::to_string(r.faces) + "," + csv_field(joined(filters, "; ")) + "," + csv_field(joined(outputs, "; ")) + "," +
           csv_field(joined(r.warnings, " | ")) + "," + csv_field(r.error) + "," + csv_field(joined(r.record, "; ")) + "\n";
    records.push_back(to_json(r));
    ++counts[r.status];
  }
  if (!fs::path(base).parent_path().empty()) fs::create_directories(fs::path(base).parent_path());
  write_text(base + ".csv", csv);
  write_text(base + ".json", json{{"files", results.size()}, {"counts", counts}, {"results", records}}.dump(1) + "\n");
}

}  // namespace reliefkit::batch
