// reliefkit-batch — the collection: which files a run (or one shard of it) processes, in a fixed
// order, and where each file's outputs and result go. No MeshLab, no Qt: unit-tested alone.
#pragma once

#include <map>
#include <string>
#include <vector>

namespace reliefkit::batch {

/// One shard of N: this run processes the files whose index in the sorted collection is
/// `index` modulo `count` (round robin, so every shard gets large and small files alike).
struct Shard {
  int index = 0;
  int count = 1;
};

/// "i/N" (0 <= i < N). Throws std::invalid_argument with a message for the user otherwise.
Shard parse_shard(const std::string& text);

/// The shard a Slurm job array task is: SLURM_ARRAY_TASK_ID - SLURM_ARRAY_TASK_MIN of
/// SLURM_ARRAY_TASK_COUNT (the array's tasks numbered from any first index, `--array=1-4` too).
/// False when the variables are not set (not run by a job array); throws when they are
/// inconsistent (a stepped array, `--array=0-15:4`, is refused with the reason).
bool shard_from_slurm(const std::map<std::string, std::string>& environment, Shard& shard);

/// Files to process: `input` itself when it is a file, or every file under it (recursively,
/// hidden folders skipped) whose extension is in `extensions` (lower case, without the dot;
/// matched case-insensitively). Sorted by path relative to the input, byte-wise — the same list on
/// every machine. Throws std::invalid_argument when the input does not exist.
std::vector<std::string> list_collection(const std::string& input, const std::vector<std::string>& extensions);

/// The part of a sorted collection that one shard processes.
std::vector<std::string> shard_of(const std::vector<std::string>& files, const Shard& shard);

/// A file's path relative to the input folder (its name when the input is a file): it names the
/// file's outputs and its result, `<output>/<relative path>/…` and
/// `<output>/.reliefkit-batch/results/<relative path>.json`.
std::string relative_to_input(const std::string& input, const std::string& file);

}  // namespace reliefkit::batch
