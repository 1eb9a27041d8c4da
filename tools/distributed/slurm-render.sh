#!/usr/bin/env bash
# Renders a scene as a Slurm job array of N shards and a merge job that waits
# for all of them (docs/distributed.md).
#
#   tools/distributed/slurm-render.sh SCENE N [sbatch options...] [-- pathtracer options...]
#
# Task K of the array (K = 0..N-1, $SLURM_ARRAY_TASK_ID) renders share K/N of
# every pixel's samples into $PT_SHARD_DIR/shard-K.ptshard; the merge job
# (--dependency=afterok:<array job>) adds them up, bit-identical to a render on
# one machine, into the -o outputs given among the pathtracer options (default
# SCENE's name with .exr). The sbatch options go to both jobs (--partition,
# --time, --cpus-per-task, --account, ...). The shard folder and the outputs
# must be on a file system every node sees.
#
# Environment: PT_EXE the pathtracer to run (default: build/pathtracer of this
# repository when it exists, else pathtracer on PATH); PT_SHARD_DIR the shard
# folder (default shards-<scene>-<date>); SBATCH the sbatch to call (default
# sbatch).
#
# Writes the job scripts render.sh and merge.sh into $PT_SHARD_DIR, prints the
# two job ids and writes $PT_SHARD_DIR/jobs.txt with them and the commands that
# re-run one failed shard and the merge.
set -euo pipefail

usage() { sed -n '2,23p' "$0" | sed 's/^# \{0,1\}//' >&2; exit 2; }
[ $# -ge 2 ] || usage
scene="$1" n="$2"
shift 2
[[ "$n" =~ ^[1-9][0-9]*$ ]] || { echo "slurm-render: N must be a positive integer, got '$n'" >&2; exit 2; }
[ -f "$scene" ] || { echo "slurm-render: no scene file '$scene'" >&2; exit 2; }

sbatch_args=() render_args=() outputs=()
while [ $# -gt 0 ] && [ "$1" != "--" ]; do sbatch_args+=("$1"); shift; done
[ $# -gt 0 ] && shift  # the "--"
while [ $# -gt 0 ]; do  # -o/--output go to the merge, the rest to every shard
  case "$1" in
    -o|--output) [ $# -ge 2 ] || usage; outputs+=("$2"); shift 2 ;;
    -o*) outputs+=("${1#-o}"); shift ;;
    --output=*) outputs+=("${1#--output=}"); shift ;;
    *) render_args+=("$1"); shift ;;
  esac
done

repo="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
if [ -z "${PT_EXE:-}" ]; then
  if [ -x "$repo/build/pathtracer" ]; then PT_EXE="$repo/build/pathtracer"; else PT_EXE="$(command -v pathtracer || true)"; fi
fi
[ -n "$PT_EXE" ] && [ -x "$PT_EXE" ] || { echo "slurm-render: no pathtracer executable (set PT_EXE)" >&2; exit 2; }
name="$(basename "${scene%.*}")"
dir="${PT_SHARD_DIR:-shards-$name-$(date +%Y%m%d-%H%M%S)}"
mkdir -p "$dir"
dir="$(cd "$dir" && pwd)"
scene="$(cd "$(dirname "$scene")" && pwd)/$(basename "$scene")"
[ ${#outputs[@]} -gt 0 ] || outputs=("$name.exr")
for i in "${!outputs[@]}"; do [[ "${outputs[$i]}" = /* ]] || outputs[$i]="$PWD/${outputs[$i]}"; done
sbatch="${SBATCH:-sbatch}"

# The two job scripts, kept in the shard folder: a failed task is re-run with
# the same script (sbatch --array=K render.sh).
q() { printf ' %q' "$@"; }
{
  echo '#!/bin/sh'
  echo "# Task \$SLURM_ARRAY_TASK_ID of $n of $(basename "$scene") (slurm-render.sh)"
  echo "exec$(q "$PT_EXE" "$scene") --shard \"\$SLURM_ARRAY_TASK_ID/$n\" --shard-out$(q "$dir")/shard-\"\$SLURM_ARRAY_TASK_ID\".ptshard$(q --quiet ${render_args[@]+"${render_args[@]}"})"
} > "$dir/render.sh"
{
  echo '#!/bin/sh'
  echo "# The merge of the $n shards of $(basename "$scene") (slurm-render.sh)"
  printf 'exec%s merge' "$(q "$PT_EXE")"
  for ((k = 0; k < n; k++)); do q "$dir/shard-$k.ptshard"; done
  for o in "${outputs[@]}"; do q -o "$o"; done
  echo
} > "$dir/merge.sh"
chmod +x "$dir/render.sh" "$dir/merge.sh"
sbatch="${SBATCH:-sbatch}"

array_job="$("$sbatch" --parsable --array="0-$((n - 1))" --job-name="pt-$name" --output="$dir/render-%a.log" \
  ${sbatch_args[@]+"${sbatch_args[@]}"} "$dir/render.sh")"
array_job="${array_job%%;*}"  # --parsable prints "id" or "id;cluster"
merge_job="$("$sbatch" --parsable --dependency="afterok:$array_job" --job-name="pt-$name-merge" \
  --output="$dir/merge.log" ${sbatch_args[@]+"${sbatch_args[@]}"} "$dir/merge.sh")"
merge_job="${merge_job%%;*}"

cat > "$dir/jobs.txt" <<JOBS
render array job $array_job: $n tasks of $dir/render.sh (logs $dir/render-K.log)
merge job $merge_job: $dir/merge.sh once every task succeeded (log $dir/merge.log)
A failed task K leaves the merge pending (DependencyNeverSatisfied). Re-run it alone; it
reproduces exactly (a sample depends on the seed, the pixel and its index only):
  $sbatch --parsable --array=K --job-name=pt-$name --output=$dir/render-%a.log$(q ${sbatch_args[@]+"${sbatch_args[@]}"}) $dir/render.sh
then let the merge wait for it: scontrol update JobId=$merge_job Dependency=afterok:<the new job>
(or cancel the merge job and run $dir/merge.sh by hand).
JOBS
echo "submitted render array $array_job ($n shards) and merge $merge_job; shards and job scripts in $dir"
