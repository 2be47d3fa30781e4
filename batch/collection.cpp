// reliefkit-batch — the collection and its shards. See collection.h.
#include "collection.h"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <stdexcept>

namespace fs = std::filesystem;

namespace reliefkit::batch {
namespace {

int parse_count(const std::string& text, const char* what) {
  size_t used = 0;
  long value = -1;
  try {
    value = std::stol(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used != text.size() || text.empty() || value < 0 || value > 1000000)
    throw std::invalid_argument(std::string(what) + " must be a whole number, not \"" + text + "\"");
  return int(value);
}

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return s;
}

bool hidden(const fs::path& p) {
  const std::string name = p.filename().string();
  return !name.empty() && name[0] == '.';
}
}  // namespace

Shard parse_shard(const std::string& text) {
  const size_t slash = text.find('/');
  if (slash == std::string::npos) throw std::invalid_argument("--shard is i/N (this run's shard i of N, 0 <= i < N), not \"" + text + "\"");
  Shard s{parse_count(text.substr(0, slash), "The shard's index"), parse_count(text.substr(slash + 1), "The number of shards")};
  if (s.count < 1 || s.index >= s.count)
    throw std::invalid_argument("--shard " + text + ": the index must be from 0 to the number of shards - 1");
  return s;
}

bool shard_from_slurm(const std::map<std::string, std::string>& environment, Shard& shard) {
  auto get = [&](const char* key) -> const std::string* {
    const auto it = environment.find(key);
    return it == environment.end() || it->second.empty() ? nullptr : &it->second;
  };
  const std::string *id = get("SLURM_ARRAY_TASK_ID"), *count = get("SLURM_ARRAY_TASK_COUNT");
  if (!id || !count) return false;
  const std::string* min = get("SLURM_ARRAY_TASK_MIN");
  const std::string* max = get("SLURM_ARRAY_TASK_MAX");
  const std::string* step = get("SLURM_ARRAY_TASK_STEP");
  Shard s{parse_count(*id, "SLURM_ARRAY_TASK_ID") - (min ? parse_count(*min, "SLURM_ARRAY_TASK_MIN") : 0),
          parse_count(*count, "SLURM_ARRAY_TASK_COUNT")};
  if (step && parse_count(*step, "SLURM_ARRAY_TASK_STEP") != 1)
    throw std::invalid_argument("the Slurm job array has a step (" + *step + "): give it consecutive task ids (--array=0-" +
                                std::to_string(s.count - 1) + ")");
  if (min && max && parse_count(*max, "SLURM_ARRAY_TASK_MAX") - parse_count(*min, "SLURM_ARRAY_TASK_MIN") + 1 != s.count)
    throw std::invalid_argument("the Slurm job array's task ids are not consecutive (--array=" + *min + "-" + *max + " with " +
                                *count + " tasks): give it a range, --array=0-" + std::to_string(s.count - 1));
  if (s.count < 1 || s.index < 0 || s.index >= s.count)
    throw std::invalid_argument("SLURM_ARRAY_TASK_ID " + *id + " is outside the array's " + *count + " tasks");
  shard = s;
  return true;
}

std::vector<std::string> list_collection(const std::string& input, const std::vector<std::string>& extensions) {
  const fs::path root(input);
  std::error_code ec;
  if (fs::is_regular_file(root, ec)) return {root.string()};
  if (!fs::is_directory(root, ec)) throw std::invalid_argument("The input " + input + " is neither a file nor a folder.");
  std::vector<std::string> files;
  for (auto it = fs::recursive_directory_iterator(root, fs::directory_options::skip_permission_denied, ec);
       it != fs::recursive_directory_iterator(); it.increment(ec)) {
    if (ec) break;
    if (hidden(it->path())) {
      if (it->is_directory()) it.disable_recursion_pending();
      continue;
    }
    if (!it->is_regular_file()) continue;
    const std::string ext = lower(it->path().extension().string());
    if (ext.size() > 1 && std::find(extensions.begin(), extensions.end(), ext.substr(1)) != extensions.end())
      files.push_back(it->path().string());
  }
  std::sort(files.begin(), files.end(), [&](const std::string& a, const std::string& b) {
    return relative_to_input(input, a) < relative_to_input(input, b);
  });
  return files;
}

std::vector<std::string> shard_of(const std::vector<std::string>& files, const Shard& shard) {
  std::vector<std::string> mine;
  for (size_t k = 0; k < files.size(); ++k)
    if (int(k % size_t(shard.count)) == shard.index) mine.push_back(files[k]);
  return mine;
}

std::string relative_to_input(const std::string& input, const std::string& file) {
  std::error_code ec;
  if (fs::is_regular_file(input, ec)) return fs::path(file).filename().string();
  return fs::path(file).lexically_relative(fs::path(input)).generic_string();
}

}  // namespace reliefkit::batch
