// reliefkit-batch — the run: each file of the shard handled by a process of its own (this program
// again, as a worker), a few at a time, their progress relayed, their memory watched. A file whose
// process dies is recorded as crashed and the run goes on; so is one that outgrows its share of
// the memory cap (stopped, recorded as "memory"). POSIX, no MeshLab.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "results.h"

namespace reliefkit::batch {

struct Job {
  std::string file, relative;
};

struct RunOptions {
  int jobs = 1;
  long memory_cap_mib = 0;          // all workers together; each may use cap / jobs
  std::vector<std::string> worker;  // the worker's command line; the job's file and relative path are appended
  std::string output;               // where the workers write their result records
  std::string shard;                // "i/N", for the records the supervisor writes
};

/// Runs the jobs; returns their results in the jobs' order. `say` gets every line to show.
std::vector<FileResult> run_jobs(const std::vector<Job>& jobs, const RunOptions& options,
                                 const std::function<void(const std::string&)>& say);

/// The machine's memory in MiB (MemTotal).
long machine_memory_mib();

/// The cores this process may run on (its CPU affinity; at least 1).
int usable_cores();

/// OpenMP threads of each of `jobs` workers on `cores` cores: cores / jobs, at least 1.
int threads_per_job(int cores, int jobs);

/// A worker's environment: `parent` ("NAME=value" entries) with each job's share of the cores
/// for OpenMP, OMP_NUM_THREADS = cores / jobs (at least 1), and OMP_WAIT_POLICY=PASSIVE (a thread
/// waiting at a barrier sleeps instead of spinning on a core another job needs); either variable
/// the caller set is kept as it is.
std::vector<std::string> worker_environment(const std::vector<std::string>& parent, int cores, int jobs);

}  // namespace reliefkit::batch
