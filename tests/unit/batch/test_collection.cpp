// reliefkit-batch's collection (batch/collection.h): the files listed, the shards, Slurm's array.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <set>

#include "collection.h"

namespace fs = std::filesystem;
using namespace reliefkit::batch;

namespace {
// A folder tree of empty files: scans in two sub-folders, a drawing, a hidden folder and a note.
std::string make_tree(const std::string& name) {
  const fs::path root = fs::temp_directory_path() / name;
  fs::remove_all(root);
  for (const char* f : {"b/coin.PLY", "a/lamp.obj", "a/seal.ply", "a/deep/tablet.stl", "plate.png", ".cache/x.ply", "notes.txt", "z.off"}) {
    fs::create_directories((root / f).parent_path());
    std::ofstream(root / f) << "x";
  }
  return root.string();
}
}  // namespace

TEST(BatchCollection, AFolderTreeIsListedSortedWithItsExtensions) {
  const std::string root = make_tree("rk_batch_tree");
  const auto files = list_collection(root, {"ply", "obj", "off", "stl"});
  std::vector<std::string> rel;
  for (const auto& f : files) rel.push_back(relative_to_input(root, f));
  // Case-insensitive extensions, hidden folders skipped, sorted by relative path.
  EXPECT_EQ(rel, (std::vector<std::string>{"a/deep/tablet.stl", "a/lamp.obj", "a/seal.ply", "b/coin.PLY", "z.off"}));
  const auto drawings = list_collection(root, {"png"});
  ASSERT_EQ(drawings.size(), 1u);
  // A single file is its own collection, named by its file name.
  const auto one = list_collection(root + "/a/seal.ply", {"obj"});
  ASSERT_EQ(one.size(), 1u);
  EXPECT_EQ(relative_to_input(root + "/a/seal.ply", one[0]), "seal.ply");
  EXPECT_THROW(list_collection(root + "/missing", {"ply"}), std::invalid_argument);
}

TEST(BatchCollection, ShardsPartitionTheCollection) {
  std::vector<std::string> files;
  for (int k = 0; k < 23; ++k) files.push_back("f" + std::to_string(100 + k));
  for (int n : {1, 2, 4, 7, 30}) {
    std::multiset<std::string> seen;
    size_t smallest = files.size(), largest = 0;
    for (int i = 0; i < n; ++i) {
      const auto part = shard_of(files, parse_shard(std::to_string(i) + "/" + std::to_string(n)));
      seen.insert(part.begin(), part.end());
      smallest = std::min(smallest, part.size());
      largest = std::max(largest, part.size());
    }
    EXPECT_EQ(seen, std::multiset<std::string>(files.begin(), files.end())) << n << " shards: every file once";
    EXPECT_LE(largest - smallest, 1u) << n << " shards: balanced";
  }
  for (const char* bad : {"3/3", "1", "-1/2", "a/b", "0/0", "1/2/3"}) EXPECT_THROW(parse_shard(bad), std::invalid_argument) << bad;
}

TEST(BatchCollection, ASlurmArrayTaskIsItsShard) {
  Shard s;
  EXPECT_FALSE(shard_from_slurm({}, s));
  EXPECT_FALSE(shard_from_slurm({{"SLURM_JOB_ID", "7"}}, s));
  ASSERT_TRUE(shard_from_slurm({{"SLURM_ARRAY_TASK_ID", "2"}, {"SLURM_ARRAY_TASK_COUNT", "4"}, {"SLURM_ARRAY_TASK_MIN", "0"},
                                {"SLURM_ARRAY_TASK_MAX", "3"}}, s));
  EXPECT_EQ(s.index, 2);
  EXPECT_EQ(s.count, 4);
  // --array=1-4: task 1 is shard 0.
  ASSERT_TRUE(shard_from_slurm({{"SLURM_ARRAY_TASK_ID", "1"}, {"SLURM_ARRAY_TASK_COUNT", "4"}, {"SLURM_ARRAY_TASK_MIN", "1"},
                                {"SLURM_ARRAY_TASK_MAX", "4"}}, s));
  EXPECT_EQ(s.index, 0);
  // A stepped or sparse array cannot be shards of one collection.
  EXPECT_THROW(shard_from_slurm({{"SLURM_ARRAY_TASK_ID", "4"}, {"SLURM_ARRAY_TASK_COUNT", "4"}, {"SLURM_ARRAY_TASK_MIN", "0"},
                                 {"SLURM_ARRAY_TASK_MAX", "12"}, {"SLURM_ARRAY_TASK_STEP", "4"}}, s),
               std::invalid_argument);
  EXPECT_THROW(shard_from_slurm({{"SLURM_ARRAY_TASK_ID", "9"}, {"SLURM_ARRAY_TASK_COUNT", "3"}, {"SLURM_ARRAY_TASK_MIN", "1"},
                                 {"SLURM_ARRAY_TASK_MAX", "9"}}, s),
               std::invalid_argument);
}
