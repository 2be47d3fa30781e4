# Sourced by the test and build scripts: named stages whose wall-clock times are printed as a table
# when the script ends (also when a stage fails, so a slow or broken stage is seen at once).
#   stage "what it does" command args...
# Runs under `set -e` as the caller does: a failing command inside a stage's function ends the script.
_stage_names=()
_stage_seconds=()
_stage_running=""
_stage_t0=0
_stages_started=$SECONDS

stage() {
  _stage_running="$1"
  _stage_t0=$SECONDS
  shift
  echo "== $_stage_running =="
  "$@"
  _stage_names+=("$_stage_running")
  _stage_seconds+=($((SECONDS - _stage_t0)))
  _stage_running=""
}

print_stages() {
  echo "== time per stage =="
  local i
  for i in "${!_stage_names[@]}"; do
    printf '%6d s  %s\n' "${_stage_seconds[$i]}" "${_stage_names[$i]}"
  done
  [ -z "$_stage_running" ] || printf '%6d s  %s  (FAILED)\n' $((SECONDS - _stage_t0)) "$_stage_running"
  printf '%6d s  total\n' $((SECONDS - _stages_started))
}
