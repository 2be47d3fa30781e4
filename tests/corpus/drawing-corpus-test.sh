#!/usr/bin/env bash
# The drawing corpus as a guard (issue 39): scripts/drawing-corpus.sh on the corpus beside the clone
# (../shared/data/drawings/corpus), its table written into the build folder; fewer drawings passing
# than docs/drawing_corpus.md records — in the tuning or the held-out part — fails the test, so that
# a change to the drawing filters that loses real drawings is seen (and one that wins them updates
# the page). Usage: drawing-corpus-test.sh BUILD_DIR
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
build="$1"
corpus="$here/../shared/data/drawings/corpus"
if [ ! -d "$corpus" ]; then echo "no corpus at $corpus: nothing to check"; exit 0; fi
out="$build/drawing-corpus-test"
bash "$here/scripts/drawing-corpus.sh" "$corpus" "$out" "$out/drawing_corpus.md" > "$out.log" 2>&1 ||
  { tail -20 "$out.log"; echo "FAIL: scripts/drawing-corpus.sh failed"; exit 1; }
passing() {  # the counts "T of N ... ; H of M ..." of a page's "Passing:" line
  grep -m1 '^\*\*Passing:' "$1" | grep -oE '[0-9]+ of [0-9]+' | cut -d' ' -f1 | tr '\n' ' '
}
read -r now_tuning now_held <<<"$(passing "$out/drawing_corpus.md")"
read -r was_tuning was_held <<<"$(passing "$here/docs/drawing_corpus.md")"
echo "passing now: $now_tuning tuning, $now_held held out; docs/drawing_corpus.md: $was_tuning, $was_held"
grep -a "^FAIL" "$out/scores.txt" || true  # the drawings failing now, for the log
if [ "$now_tuning" -lt "$was_tuning" ] || [ "$now_held" -lt "$was_held" ]; then
  echo "FAIL: fewer drawings pass than docs/drawing_corpus.md records"
  exit 1
fi
echo "the corpus holds: as many drawings pass as recorded"
