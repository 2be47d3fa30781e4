// reliefkit-batch — what became of each file: its result record (one JSON file per input file,
// written when the file is done, so that a resumed run skips it), and the summaries (CSV and
// JSON) of a run, of a shard, or of all shards merged. No MeshLab, no Qt.
#pragma once

#include <string>
#include <vector>

namespace reliefkit::batch {

struct LayerOutput {
  std::string layer, file;  // the layer's name; its file, relative to the output folder
  long vertices = 0, faces = 0, edges = 0;
};

struct FilterRun {
  std::string filter;
  double seconds = 0;
  bool ok = false;
  std::vector<std::string> parameters;  // "name=value", as the filter ran
};

/// status: "ok"; "failed" (the file could not be read, a filter refused it or failed, an output
/// could not be written: `error` says which and why); "crashed" (the process handling the file
/// died: `error` names the signal or exit code and the last lines it printed); "memory" (stopped
/// at its share of the memory cap).
struct FileResult {
  std::string file;  // relative to the input folder
  std::string status;
  double seconds = 0;
  long vertices = 0, faces = 0;  // of the file as read
  long peak_memory_mib = 0;
  std::vector<FilterRun> filters;
  std::vector<LayerOutput> outputs;
  std::vector<std::string> warnings;  // the filters' log lines that warn
  std::vector<std::string> record;    // "name=value": the measures filters log as "Record: a=1; b=2" (a sherd's rim diameter...)
  std::string error;
  std::string shard;  // "i/N"
};

/// <output>/.reliefkit-batch/results/<relative path>.json
std::string result_path(const std::string& output, const std::string& relative);
/// False when there is no readable record.
bool read_result(const std::string& path, FileResult& result);
/// Written to a temporary file and renamed: a record is complete or absent.
void write_result(const std::string& path, const FileResult& result);

/// A file is done when its record exists; with `retry_failed`, only when it succeeded.
bool is_done(const std::string& output, const std::string& relative, bool retry_failed);

/// Every record under <output>/.reliefkit-batch/results (all shards), sorted by file.
std::vector<FileResult> all_results(const std::string& output);

/// <base>.csv (one line per file: file, status, seconds, vertices, faces, filters, outputs,
/// warnings, error, record) and <base>.json (the records and the counts per status).
void write_summary(const std::string& base, const std::vector<FileResult>& results);

/// "12 ok, 1 failed, 0 crashed, 0 memory".
std::string status_counts(const std::vector<FileResult>& results);

}  // namespace reliefkit::batch
