#!/usr/bin/env bash
# One long clip on Slurm (docs/scale.md): an array with one task per segment, then a gather job
# that joins them once every task has succeeded (--dependency=afterok).
#   deploy/slurm/clip.sh SCENE OUT.mp4 [render options]
# The segments go to OUT.segments/ (a directory the tasks share; it must be on a file system
# every node sees). Prints the two job ids. A failed task can be run again with
# `scontrol requeue JOBID_TASK`; the gather job waits for it. SBATCH_ARGS adds sbatch options
# to both (e.g. "--partition=render"), MAX_TASKS caps the segments rendered at once, and
# DISCREEL names the binary if it is not `discreel` on the PATH.
set -euo pipefail
[[ $# -ge 2 ]] || { echo "usage: $0 SCENE OUT.mp4|.mkv|.webm [render options]" >&2; exit 2; }
readonly scene="$1" out="$2"
shift 2
readonly here="$(cd "$(dirname "$0")" && pwd)" discreel="${DISCREEL:-discreel}"
# The render is checked here, before anything is submitted; its plan says how many segments.
plan="$("$discreel" render "$scene" -o "$out" "$@" --dry-run)"
count="$(sed -n 's/^segments=//p' <<<"$plan")"
format="$(sed -n 's/^format=//p' <<<"$plan")"
[[ $count -ge 1 ]] || { echo "$out is not a video made of segments (.mp4, .mkv, .webm)" >&2; exit 2; }
readonly dir="${out%.*}.segments"
mkdir -p "$dir"
read -r -a extra <<<"${SBATCH_ARGS:-}"
export DISCREEL="$discreel"
array="$(sbatch --parsable "${extra[@]}" --array="0-$((count - 1))${MAX_TASKS:+%$MAX_TASKS}" \
  "$here/segment.sbatch" "$scene" "$dir" "$format" "$@")"
gather="$(sbatch --parsable "${extra[@]}" --dependency="afterok:$array" --kill-on-invalid-dep=yes \
  "$here/gather.sbatch" "$dir" "$out")"
echo "$array $gather"
