// reliefkit-batch's records and summaries (batch/results.h) and its supervisor (batch/supervisor.h)
// with small shell scripts as workers: a record kept, a crash recorded, a job over its memory share
// stopped, jobs in parallel.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "results.h"
#include "supervisor.h"

namespace fs = std::filesystem;
using namespace reliefkit::batch;

namespace {
std::string fresh_dir(const std::string& name) {
  const fs::path d = fs::temp_directory_path() / name;
  fs::remove_all(d);
  fs::create_directories(d);
  return d.string();
}

std::string read_text(const std::string& path) {
  std::ifstream f(path);
  std::stringstream s;
  s << f.rdbuf();
  return s.str();
}

FileResult sample(const std::string& file, const std::string& status) {
  FileResult r;
  r.file = file;
  r.status = status;
  r.seconds = 1.5;
  r.vertices = 10;
  r.faces = 16;
  r.filters = {{"Demarcating Curves", 1.25, status == "ok"}};
  r.outputs = {{"coin – demarcating curves", "coin/curves.obj", 40, 0, 39}};
  r.warnings = {"Demarcating Curves: Warning: 3 short pieces, \"dropped\""};
  r.error = status == "ok" ? "" : "it failed, badly";
  r.shard = "0/1";
  if (status == "ok") r.record = {"rim_diameter=57.3", "eve=0.31"};
  return r;
}
}  // namespace

TEST(BatchResults, RecordsRoundTripAndDecideWhatIsDone) {
  const std::string out = fresh_dir("rk_batch_records");
  write_result(result_path(out, "a/coin.ply"), sample("a/coin.ply", "ok"));
  write_result(result_path(out, "b/seal.ply"), sample("b/seal.ply", "crashed"));
  FileResult back;
  ASSERT_TRUE(read_result(result_path(out, "a/coin.ply"), back));
  EXPECT_EQ(back.outputs.at(0).layer, "coin – demarcating curves");
  EXPECT_EQ(back.warnings.at(0), "Demarcating Curves: Warning: 3 short pieces, \"dropped\"");
  EXPECT_EQ(back.record, std::vector<std::string>({"rim_diameter=57.3", "eve=0.31"}));
  EXPECT_DOUBLE_EQ(back.filters.at(0).seconds, 1.25);
  EXPECT_TRUE(is_done(out, "a/coin.ply", false));
  EXPECT_TRUE(is_done(out, "b/seal.ply", false));   // a crash is recorded: the run goes on past it
  EXPECT_FALSE(is_done(out, "b/seal.ply", true));   // --retry-failed
  EXPECT_FALSE(is_done(out, "c/lamp.ply", false));  // never started, or interrupted
  std::ofstream(result_path(out, "c/lamp.ply")) << "{\"file\": \"c/la";  // a damaged record counts as none
  EXPECT_FALSE(is_done(out, "c/lamp.ply", false));
}

TEST(BatchResults, SummaryCsvQuotesAndMergeReadsEveryShard) {
  const std::string out = fresh_dir("rk_batch_merge");
  write_result(result_path(out, "b/seal.ply"), sample("b/seal.ply", "failed"));
  write_result(result_path(out, "a/coin.ply"), sample("a/coin.ply", "ok"));
  const auto all = all_results(out);
  ASSERT_EQ(all.size(), 2u);
  EXPECT_EQ(all[0].file, "a/coin.ply");
  EXPECT_EQ(status_counts(all), "1 ok, 1 failed, 0 crashed, 0 memory");
  write_summary(out + "/summary", all);
  const std::string csv = read_text(out + "/summary.csv");
  EXPECT_EQ(csv.substr(0, csv.find('\n')), "file,status,seconds,vertices,faces,filters,outputs,warnings,error,record");
  EXPECT_NE(csv.find("a/coin.ply,ok,1.50,10,16,Demarcating Curves,coin/curves.obj,"
                     "\"Demarcating Curves: Warning: 3 short pieces, \"\"dropped\"\"\",,rim_diameter=57.3; eve=0.31\n"),
            std::string::npos)
      << csv;
  EXPECT_NE(csv.find("b/seal.ply,failed,1.50,10,16,Demarcating Curves (failed),coin/curves.obj,"), std::string::npos);
  EXPECT_NE(read_text(out + "/summary.json").find("\"failed\": 1"), std::string::npos);
}

// Workers are shell scripts here: `sh -c SCRIPT sh OUTPUT FILE RELATIVE` (the supervisor appends
// FILE and RELATIVE to the worker's command).
TEST(BatchSupervisor, CrashesAndMemoryAreRecordedAndTheRunGoesOn) {
  const std::string out = fresh_dir("rk_batch_supervisor");
  const std::string script =
      "case \"$2\" in"
      "  *crash*) echo about to fail; kill -SEGV $$ ;;"
      "  *big*) echo growing; x=$(head -c 150000000 /dev/zero | tr '\\0' a); echo \"${#x}\" ;;"
      "  *) mkdir -p \"$(dirname \"$1/.reliefkit-batch/results/$3\")\";"
      "     printf '{\"file\":\"%s\",\"status\":\"ok\"}' \"$3\" > \"$1/.reliefkit-batch/results/$3.json\" ;;"
      "esac";
  RunOptions o;
  o.jobs = 2;
  o.memory_cap_mib = 2 * 60;  // 60 MiB each
  o.worker = {"/bin/sh", "-c", script, "sh", out};
  o.output = out;
  o.shard = "0/1";
  std::vector<std::string> lines;
  const auto t0 = std::chrono::steady_clock::now();
  const auto results = run_jobs({{"/x/one.ply", "one.ply"}, {"/x/crash.ply", "crash.ply"}, {"/x/big.ply", "big.ply"},
                                 {"/x/two.ply", "sub/two.ply"}},
                                o, [&](const std::string& l) { lines.push_back(l); });
  ASSERT_EQ(results.size(), 4u);
  EXPECT_EQ(results[0].status, "ok");
  EXPECT_EQ(results[1].status, "crashed");
  EXPECT_NE(results[1].error.find("signal 11"), std::string::npos) << results[1].error;
  EXPECT_NE(results[1].error.find("about to fail"), std::string::npos) << results[1].error;  // its last lines
  EXPECT_EQ(results[2].status, "memory") << results[2].error;
  EXPECT_GE(results[2].peak_memory_mib, 60);
  EXPECT_EQ(results[3].status, "ok");
  EXPECT_EQ(results[3].file, "sub/two.ply");
  // Every outcome is on disk, for a resumed run.
  for (const char* rel : {"one.ply", "crash.ply", "big.ply", "sub/two.ply"}) EXPECT_TRUE(is_done(out, rel, false)) << rel;
  bool tagged = false;
  for (const auto& l : lines) tagged = tagged || l == "[2/4 crash.ply] about to fail";
  EXPECT_TRUE(tagged);
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(), 30.0);
}

// A supervisor bigger than a worker's share (an instrumented test binary is): each worker is
// measured as its own program from its first reading, never as the copy of the supervisor a fork
// makes before it runs the worker.
TEST(BatchSupervisor, AWorkerIsMeasuredAsItselfNotAsACopyOfALargeSupervisor) {
  const std::string out = fresh_dir("rk_batch_large_supervisor");
  const std::vector<char> ballast(size_t(200) << 20, 1);  // 200 MiB, resident
  RunOptions o;
  o.jobs = 2;
  o.memory_cap_mib = 2 * 60;
  o.worker = {"/bin/sh", "-c", "echo started; echo done", "sh", out};
  o.output = out;
  o.shard = "0/1";
  std::vector<Job> jobs;
  for (int k = 0; k < 20; ++k) jobs.push_back({"/x/f" + std::to_string(k) + ".ply", "f" + std::to_string(k) + ".ply"});
  const auto results = run_jobs(jobs, o, [](const std::string&) {});
  int stopped = 0;
  for (const auto& r : results) stopped += r.status == "memory";
  EXPECT_EQ(stopped, 0);
  EXPECT_EQ(ballast.back(), 1);
}

// Each job gets its share of the cores and passive waiting; what the caller set stays.
TEST(BatchSupervisor, EachWorkerGetsItsShareOfTheCoresAndWaitsPassively) {
  auto value = [](const std::vector<std::string>& env, const std::string& name) {
    std::string found = "(unset)";
    int count = 0;
    for (const auto& e : env)
      if (e.rfind(name + "=", 0) == 0) found = e.substr(name.size() + 1), ++count;
    return count > 1 ? "(twice)" : found;
  };
  const std::vector<std::string> plain{"PATH=/usr/bin", "HOME=/root"};
  EXPECT_EQ(value(worker_environment(plain, 8, 1), "OMP_NUM_THREADS"), "8");
  EXPECT_EQ(value(worker_environment(plain, 8, 2), "OMP_NUM_THREADS"), "4");
  EXPECT_EQ(value(worker_environment(plain, 8, 3), "OMP_NUM_THREADS"), "2");
  EXPECT_EQ(value(worker_environment(plain, 2, 4), "OMP_NUM_THREADS"), "1");
  EXPECT_EQ(value(worker_environment(plain, 2, 2), "OMP_WAIT_POLICY"), "PASSIVE");
  EXPECT_EQ(value(worker_environment(plain, 2, 2), "PATH"), "/usr/bin");
  const std::vector<std::string> set{"OMP_NUM_THREADS=3", "OMP_WAIT_POLICY=ACTIVE"};
  EXPECT_EQ(value(worker_environment(set, 8, 2), "OMP_NUM_THREADS"), "3");
  EXPECT_EQ(value(worker_environment(set, 8, 2), "OMP_WAIT_POLICY"), "ACTIVE");
  EXPECT_GE(usable_cores(), 1);
}

// The environment reaches the workers: a worker prints what it was given.
TEST(BatchSupervisor, WorkersRunWithTheirShareOfThreads) {
  const std::string out = fresh_dir("rk_batch_threads");
  RunOptions o;
  o.jobs = 2 * usable_cores();
  o.worker = {"/bin/sh", "-c", "echo \"threads=$OMP_NUM_THREADS policy=$OMP_WAIT_POLICY\"", "sh", out};
  o.output = out;
  o.shard = "0/1";
  std::vector<std::string> lines;
  unsetenv("OMP_NUM_THREADS");
  unsetenv("OMP_WAIT_POLICY");
  run_jobs({{"/x/a.ply", "a.ply"}}, o, [&](const std::string& l) { lines.push_back(l); });
  EXPECT_NE(std::find(lines.begin(), lines.end(), "[1/1 a.ply] threads=1 policy=PASSIVE"), lines.end());
}
