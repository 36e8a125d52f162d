#!/usr/bin/env bash
# Copies what `shadesweep report` reads from the output folders under OUTDIR into DEST,
# so that a committed reproduction can be reported again from the repository alone:
#   scripts/keep-results.sh OUTDIR DEST
# Kept: each folder's plan.csv, summary.csv, summary.md and sweep.yaml, and of each run
# meta.yaml, summary.csv, seconds.csv, passes.csv, errors.csv and coverage.csv. Left
# out: frames.csv (every frame: most of the bytes; the report does not need it where
# coverage.csv exists), convergence.csv, images, logs, files.txt (it lists the files
# left out) and the lock. DEST must not exist: nothing is overwritten.
set -euo pipefail
[ $# -eq 2 ] || { echo "usage: scripts/keep-results.sh OUTDIR DEST" >&2; exit 2; }
src=$1 dest=$2
[ -d "$src" ] || { echo "keep-results: $src: no such folder" >&2; exit 2; }
[ ! -e "$dest" ] || { echo "keep-results: $dest exists; choose a new folder" >&2; exit 2; }
n=0
while IFS= read -r -d '' plan; do
  folder=$(dirname "$plan")
  rel=${folder#"$src"}; rel=${rel#/}
  [ -f "$folder/summary.csv" ] || continue
  mkdir -p "$dest/$rel"
  for f in plan.csv summary.csv summary.md sweep.yaml; do
    [ -f "$folder/$f" ] && cp "$folder/$f" "$dest/$rel/$f"
  done
  for run in "$folder"/runs/*/; do
    [ -d "$run" ] || continue
    id=$(basename "$run")
    mkdir -p "$dest/$rel/runs/$id"
    for f in meta.yaml summary.csv seconds.csv passes.csv errors.csv coverage.csv; do
      [ -f "$run/$f" ] && cp "$run/$f" "$dest/$rel/runs/$id/$f"
    done
  done
  n=$((n + 1))
done < <(find "$src" -maxdepth 3 -name plan.csv -print0 | sort -z)
[ "$n" -gt 0 ] || { echo "keep-results: no output folder (plan.csv and summary.csv) under $src" >&2; exit 1; }
echo "keep-results: $n output folder(s) into $dest ($(du -sh "$dest" | cut -f1))" >&2
