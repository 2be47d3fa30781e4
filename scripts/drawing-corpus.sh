#!/usr/bin/env bash
# The corpus of real drawings at defaults (issue 39): every pottery drawing through "Vessel from
# Profile Drawing", every other one through "Relief from Line Drawing", in reliefkit-batch; each
# result scored with the checks that need no annotation (tests/support/drawing_scores.h) by
# build/bench/score_drawing_corpus, which writes docs/drawing_corpus.md (the figures) and, in OUT/pictures,
# each drawing beside its result with the same table (drawing_corpus.md there): the drawings' terms
# do not allow them in the repository.
#
#   scripts/drawing-corpus.sh [CORPUS] [OUT] [PAGE]
#
# CORPUS (default ../shared/data/drawings/corpus) holds one folder per kind (pottery, lithics,
# other); OUT (default build/drawing-corpus) the batch outputs; PAGE (default docs/drawing_corpus.md)
# the table. The held-out part — never tuned
# on — is the first 30 % (rounded up) of each kind in the order of the SHA-1 of the file names,
# so any corpus is split the same way, before anything is run.
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
corpus="$(cd "${1:-$here/../shared/data/drawings/corpus}" && pwd)"
out="${2:-$here/build/drawing-corpus}"
page="${3:-$here/docs/drawing_corpus.md}"
batch="$here/build/prefix/bin/reliefkit-batch"
score="$here/build/bench/score_drawing_corpus"
[ -x "$batch" ] && [ -x "$score" ] || bash "$here/scripts/build.sh" --target prefix --target score_drawing_corpus
rm -rf "$out"; mkdir -p "$out"

: > "$out/held-out.txt"
for kind in "$corpus"/*/; do
  names=$(cd "$kind" && ls | grep -Ei '\.(png|jpg)$' || true)
  n=$(printf '%s\n' "$names" | grep -c . || true)
  [ "$n" -gt 0 ] || continue
  for f in $names; do printf '%s %s\n' "$(printf '%s' "$f" | sha1sum | cut -c1-40)" "$f"; done |
    sort | head -n $(( (3 * n + 9) / 10 )) | cut -d' ' -f2 >> "$out/held-out.txt"
done

for kind in "$corpus"/*/; do
  name=$(basename "$kind")
  filter="Relief from Line Drawing"
  [ "$name" = pottery ] && filter="Vessel from Profile Drawing"
  echo "== $name: $filter"
  "$batch" --filter "$filter" --param "drawing={input}" --extensions png,jpg --save new --jobs 2 \
    "$kind" "$out/$name" > "$out/$name.log" 2>&1 || true  # refusals are scored, not fatal
  tail -1 "$out/$name.log"
done

"$score" --corpus "$corpus" --results "$out" --held-out "$out/held-out.txt" \
  --page "$page" --pictures "$out/pictures" | tee "$out/scores.txt"
