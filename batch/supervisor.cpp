// reliefkit-batch — the supervisor of the workers. See supervisor.h.
#include "supervisor.h"

#include <fcntl.h>
#include <poll.h>
#include <sched.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstring>
#include <deque>
#include <fstream>
#include <sstream>

namespace reliefkit::batch {
namespace {

using Clock = std::chrono::steady_clock;

// One worker process and what is known of it.
struct Worker {
  size_t job = 0;
  pid_t pid = -1;
  int out = -1;  // its stdout and stderr
  std::string pending;
  std::deque<std::string> last_lines;
  long peak_mib = 0;
  bool over_memory = false;
  Clock::time_point started;
};

long status_field_kib(pid_t pid, const char* key) {
  std::ifstream f("/proc/" + std::to_string(pid) + "/status");
  std::string line;
  while (std::getline(f, line))
    if (line.rfind(key, 0) == 0) return std::atol(line.c_str() + std::strlen(key));
  return 0;
}

// posix_spawn, not fork: the supervisor resumes only once the worker runs its own program, so the
// memory watch never reads the resident size of a copy of the supervisor (an instrumented test
// binary's copy is over a small share of the cap).
Worker start_worker(size_t index, const Job& job, const RunOptions& o, const std::vector<std::string>& env) {
  int fds[2];
  if (pipe2(fds, O_CLOEXEC) != 0) throw std::runtime_error("pipe failed");  // no other worker inherits it
  std::vector<std::string> args = o.worker;
  args.push_back(job.file);
  args.push_back(job.relative);
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  std::vector<char*> envp;
  for (const auto& e : env) envp.push_back(const_cast<char*>(e.c_str()));
  envp.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_adddup2(&actions, fds[1], STDOUT_FILENO);
  posix_spawn_file_actions_adddup2(&actions, fds[1], STDERR_FILENO);
  pid_t pid = -1;
  const int failed = posix_spawn(&pid, argv[0], &actions, nullptr, argv.data(), envp.data());
  posix_spawn_file_actions_destroy(&actions);
  if (failed) {
    close(fds[0]);
    close(fds[1]);
    throw std::runtime_error("cannot start the worker " + args[0] + ": " + std::strerror(failed));
  }
  close(fds[1]);
  Worker w;
  w.job = index;
  w.pid = pid;
  w.out = fds[0];
  w.started = Clock::now();
  return w;
}

// The worker's new output, relayed line by line with the file's name; the last lines kept for a
// crash report. False at the end of its output.
bool relay_output(Worker& w, const std::string& tag, const std::function<void(const std::string&)>& say) {
  char buf[4096];
  const ssize_t n = read(w.out, buf, sizeof buf);
  if (n <= 0) return false;
  w.pending.append(buf, size_t(n));
  size_t eol;
  while ((eol = w.pending.find('\n')) != std::string::npos) {
    const std::string line = w.pending.substr(0, eol);
    w.pending.erase(0, eol + 1);
    say(tag + line);
    w.last_lines.push_back(line);
    if (w.last_lines.size() > 12) w.last_lines.pop_front();
  }
  return true;
}

// What to do when MeshLab's importer stopped on the file (Debian builds MeshLab with assertions,
// and its OBJ importer fails one on some files).
std::string importer_hint(const std::deque<std::string>& last_lines) {
  for (const auto& l : last_lines)
    if (l.find("Assertion") != std::string::npos && l.find("import_") != std::string::npos)
      return ". MeshLab's importer stopped on this file: convert it to PLY (for an OBJ: assimp export scan.obj scan.ply "
             "-jiv, from Debian's assimp-utils) and run it again";
  return "";
}

// The record of a finished worker: its own, or one saying how it ended.
FileResult outcome(const Worker& w, const Job& job, int wait_status, const RunOptions& o) {
  FileResult r;
  const std::string path = result_path(o.output, job.relative);
  if (WIFEXITED(wait_status) && WEXITSTATUS(wait_status) == 0 && read_result(path, r)) {
    r.peak_memory_mib = w.peak_mib;
    write_result(path, r);
    return r;
  }
  r.file = job.relative;
  r.shard = o.shard;
  r.seconds = std::chrono::duration<double>(Clock::now() - w.started).count();
  r.peak_memory_mib = w.peak_mib;
  std::ostringstream why;
  if (w.over_memory) {
    r.status = "memory";
    why << "stopped at " << w.peak_mib << " MiB, over its share of the memory cap (" << o.memory_cap_mib / o.jobs
        << " MiB = cap / jobs): run it with fewer jobs (--jobs) or a larger --memory-cap";
  } else {
    r.status = "crashed";
    if (WIFSIGNALED(wait_status)) why << "the process handling it died of signal " << WTERMSIG(wait_status) << " (" << strsignal(WTERMSIG(wait_status)) << ")";
    else why << "the process handling it ended with status " << WEXITSTATUS(wait_status) << " and no result";
  }
  why << importer_hint(w.last_lines);
  if (!w.last_lines.empty()) {
    why << "; its last lines:";
    for (const auto& l : w.last_lines) why << " | " << l;
  }
  r.error = why.str();
  write_result(path, r);
  return r;
}

// Each worker's memory against its share of the cap; one over it is stopped.
void watch_memory(std::vector<Worker>& running, const RunOptions& o) {
  const long share = o.memory_cap_mib > 0 ? o.memory_cap_mib / o.jobs : 0;
  for (Worker& w : running) {
    const long mib = status_field_kib(w.pid, "VmRSS:") / 1024;
    w.peak_mib = std::max(w.peak_mib, mib);
    if (share > 0 && mib > share && !w.over_memory) {
      w.over_memory = true;
      kill(w.pid, SIGKILL);
    }
  }
}
}  // namespace

long machine_memory_mib() {
  std::ifstream f("/proc/meminfo");
  std::string key;
  long kib = 0;
  while (f >> key >> kib)
    if (key == "MemTotal:") return kib / 1024;
  return 0;
}

int usable_cores() {
  cpu_set_t set;
  if (sched_getaffinity(0, sizeof set, &set) != 0) return 1;
  return std::max(1, CPU_COUNT(&set));
}

int threads_per_job(int cores, int jobs) { return std::max(1, cores / std::max(1, jobs)); }

std::vector<std::string> worker_environment(const std::vector<std::string>& parent, int cores, int jobs) {
  std::vector<std::string> env = parent;
  auto given = [&](const std::string& name) {
    return std::any_of(env.begin(), env.end(), [&](const std::string& e) { return e.rfind(name + "=", 0) == 0; });
  };
  if (!given("OMP_NUM_THREADS")) env.push_back("OMP_NUM_THREADS=" + std::to_string(threads_per_job(cores, jobs)));
  if (!given("OMP_WAIT_POLICY")) env.push_back("OMP_WAIT_POLICY=PASSIVE");
  return env;
}

std::vector<FileResult> run_jobs(const std::vector<Job>& jobs, const RunOptions& o,
                                 const std::function<void(const std::string&)>& say) {
  std::vector<std::string> parent;
  for (char** e = environ; *e; ++e) parent.emplace_back(*e);
  const std::vector<std::string> env = worker_environment(parent, usable_cores(), o.jobs);
  std::vector<FileResult> results(jobs.size());
  std::vector<Worker> running;
  size_t next = 0, done = 0;
  auto tag = [&](size_t k) { return "[" + std::to_string(k + 1) + "/" + std::to_string(jobs.size()) + " " + jobs[k].relative + "] "; };
  while (done < jobs.size()) {
    while (running.size() < size_t(std::max(1, o.jobs)) && next < jobs.size()) {
      say(tag(next) + "started");
      running.push_back(start_worker(next, jobs[next], o, env));
      ++next;
    }
    std::vector<pollfd> fds;
    for (const Worker& w : running) fds.push_back({w.out, POLLIN, 0});
    poll(fds.data(), fds.size(), 200);
    watch_memory(running, o);
    for (size_t k = 0; k < running.size();) {
      Worker& w = running[k];
      if ((fds[k].revents & (POLLIN | POLLHUP)) && relay_output(w, tag(w.job), say)) { ++k; continue; }
      if (!(fds[k].revents & (POLLIN | POLLHUP | POLLERR))) { ++k; continue; }
      close(w.out);
      int status = 0;
      waitpid(w.pid, &status, 0);
      results[w.job] = outcome(w, jobs[w.job], status, o);
      const FileResult& r = results[w.job];
      say(tag(w.job) + r.status + (r.error.empty() ? "" : ": " + r.error.substr(0, 300)));
      ++done;
      fds.erase(fds.begin() + long(k));
      running.erase(running.begin() + long(k));
    }
  }
  return results;
}

}  // namespace reliefkit::batch
