#!/usr/bin/env bash
# reliefkit-batch under a real Slurm: a single-node cluster on this machine (munged, slurmctld and
# slurmd from Debian's packages, configured here on loopback in a temporary folder), a 4-task job
# array of examples/slurm/reliefkit-array.sbatch over a small collection, then `reliefkit-batch
# merge`; every file must be done once, by the shard its index gives. Where slurmd cannot run here
# (not root, the daemons missing or not registering), the test says why and runs the same four
# shards with GNU parallel instead — not a skip.
#   tests/slurm/slurm-array-test.sh BUILD_DIR
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
build="$(cd "${1:?usage: slurm-array-test.sh BUILD_DIR}" && pwd)"
batch="$build/prefix/bin/reliefkit-batch"
[ -x "$batch" ] || { echo "FAIL: $batch missing (build first)"; exit 1; }
work="$(mktemp -d /tmp/rk-slurm.XXXXXX)"
pids=()
cleanup() {
  for p in "${pids[@]}"; do kill "$p" 2>/dev/null || true; done
  sleep 0.5
  for p in "${pids[@]}"; do kill -9 "$p" 2>/dev/null || true; done
  [ "${RK_KEEP:-0}" = 1 ] || rm -rf "$work"
}
trap cleanup EXIT

# The collection: six copies of the bundled coin scan in two folders; the recipe: curvature shading.
mkdir -p "$work/scans/left" "$work/scans/right"
for k in 1 2 3; do
  cp "$here/examples/data/penny.ply" "$work/scans/left/coin$k.ply"
  cp "$here/examples/data/penny.ply" "$work/scans/right/coin$k.ply"
done
cat > "$work/shade.mlx" <<'EOF'
<!DOCTYPE FilterScript>
<FilterScript>
 <filter name="Curvature Shading"/>
</FilterScript>
EOF
out="$work/out"

# Checks the merged summary: six files, all ok, each once, from all four shards.
check_results() {
  "$batch" merge "$out" || { echo "FAIL: reliefkit-batch merge"; exit 1; }
  local ok; ok="$(grep -c ',ok,' "$out/summary.csv" || true)"
  [ "$ok" = 6 ] || { echo "FAIL: $ok of 6 files ok"; cat "$out/summary.csv"; exit 1; }
  for i in 0 1 2 3; do
    [ -f "$out/summary-shard-$i-of-4.csv" ] || { echo "FAIL: shard $i wrote no summary"; exit 1; }
  done
  local shards; shards="$(grep -ho '"shard": "[0-9]/4"' "$out"/.reliefkit-batch/results/*/*.json | sort | uniq -c | tr -s ' ')"
  echo "files per shard: $(echo $shards)"
  [ "$(echo "$shards" | wc -l)" = 4 ] || { echo "FAIL: the files were not spread over the four shards"; exit 1; }
}

# A single-node Slurm on loopback; false, with the reason in $why, if it cannot run here.
why=""
start_slurm() {
  [ "$(id -u)" -eq 0 ] || { why="not root (slurmd runs jobs as their users and needs root)"; return 1; }
  for d in munged slurmctld slurmd sbatch; do
    command -v "$d" >/dev/null || { why="$d missing (Debian packages munge and slurm-wlm)"; return 1; }
  done
  local node; node="$(hostname -s)"
  mkdir -p "$work/slurm/state" "$work/slurm/spool" "$work/munge"
  chmod 700 "$work/munge"
  dd if=/dev/urandom of="$work/munge/munge.key" bs=1024 count=1 status=none
  chmod 400 "$work/munge/munge.key"
  munged --force --key-file="$work/munge/munge.key" --socket="$work/munge/socket" \
    --pid-file="$work/munge/munged.pid" --log-file="$work/munge/munged.log" --seed-file="$work/munge/seed" ||
    { why="munged would not start: $(tail -2 "$work/munge/munged.log" 2>/dev/null)"; return 1; }
  pids+=("$(cat "$work/munge/munged.pid")")
  local cpus mem; cpus="$(nproc)"; mem="$(awk '/MemTotal/ {print int($2 / 1024 * 0.8)}' /proc/meminfo)"
  cat > "$work/slurm/slurm.conf" <<EOF
ClusterName=reliefkit-test
SlurmctldHost=$node(127.0.0.1)
SlurmctldPort=${RK_SLURMCTLD_PORT:-16817}
SlurmdPort=${RK_SLURMD_PORT:-16818}
AuthType=auth/munge
AuthInfo=socket=$work/munge/socket
CredType=cred/munge
SlurmUser=root
SlurmdUser=root
StateSaveLocation=$work/slurm/state
SlurmdSpoolDir=$work/slurm/spool
SlurmctldPidFile=$work/slurm/slurmctld.pid
SlurmdPidFile=$work/slurm/slurmd.pid
SlurmctldLogFile=$work/slurm/slurmctld.log
SlurmdLogFile=$work/slurm/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
SchedulerType=sched/builtin
SelectType=select/cons_tres
SelectTypeParameters=CR_Core_Memory
ReturnToService=2
MpiDefault=none
NodeName=$node NodeAddr=127.0.0.1 CPUs=$cpus RealMemory=$mem State=UNKNOWN
PartitionName=test Nodes=$node Default=YES MaxTime=INFINITE State=UP
EOF
  export SLURM_CONF="$work/slurm/slurm.conf"
  slurmctld -D -f "$SLURM_CONF" > "$work/slurm/slurmctld.out" 2>&1 & pids+=($!)
  slurmd -D -f "$SLURM_CONF" > "$work/slurm/slurmd.out" 2>&1 & pids+=($!)
  for _ in $(seq 60); do
    sinfo -h -N -o '%T' 2>/dev/null | grep -qE '^(idle|mixed)' && return 0
    sleep 0.5
  done
  why="the node did not come up in 30 s: $(tail -3 "$work/slurm/slurmd.log" "$work/slurm/slurmd.out" 2>/dev/null | tr '\n' ' ')"
  return 1
}

if start_slurm; then
  echo "Slurm $(sinfo -V | cut -d' ' -f2) on $(hostname -s): a 4-task job array"
  cd "$work"
  RELIEFKIT_BATCH="$batch" sbatch --wait --array=0-3 --cpus-per-task=1 --mem=2G --output="$work/task-%a.log" \
    "$here/examples/slurm/reliefkit-array.sbatch" "$work/shade.mlx" "$work/scans" "$out" ||
    { echo "FAIL: the job array failed"; tail -5 "$work"/task-*.log; exit 1; }
  for i in 0 1 2 3; do grep -q "shard $i/4" "$work/task-$i.log" || { echo "FAIL: task $i did not run shard $i"; cat "$work/task-$i.log"; exit 1; }; done
  check_results
  echo "PASS: Slurm job array of 4 tasks, 6 files"
else
  echo "slurmd cannot run here: $why"
  echo "running the same four shards with GNU parallel instead"
  command -v parallel >/dev/null || { echo "FAIL: GNU parallel missing too (Debian package parallel)"; exit 1; }
  parallel -j 2 "$batch" --script "$work/shade.mlx" --shard {}/4 "$work/scans" "$out" ::: 0 1 2 3 ||
    { echo "FAIL: a shard failed under GNU parallel"; exit 1; }
  check_results
  echo "PASS: 4 shards under GNU parallel (fallback: $why)"
fi
