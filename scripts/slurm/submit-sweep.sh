#!/usr/bin/env bash
# Submits a dicsynth sweep as a Slurm job array of SHARDS tasks plus its merge job (which runs once
# every task succeeded) and prints the two job ids: "ARRAY_JOB MERGE_JOB".
#
#   scripts/slurm/submit-sweep.sh SHARDS SCENE.lua OUTDIR [sweep options ...]
#
# Extra sbatch options (partition, time, GPUs) go in SBATCH_EXTRA, e.g.
#   SBATCH_EXTRA="--partition=gpu --gres=gpu:1 --time=02:00:00" scripts/slurm/submit-sweep.sh 16 ...
# The tasks' logs go to OUTDIR/slurm/ (created here).
set -euo pipefail
(($# >= 3)) || { echo "usage: $0 SHARDS SCENE.lua OUTDIR [sweep options ...]" >&2; exit 2; }
shards=$1 scene=$2 out=$3
shift 3
[[ $shards =~ ^[1-9][0-9]*$ ]] || { echo "$0: SHARDS must be a positive integer, not '$shards'" >&2; exit 2; }
here=$(cd "$(dirname "$0")" && pwd)
mkdir -p "$out/slurm"
# shellcheck disable=SC2086  # SBATCH_EXTRA is a list of options
array=$(sbatch --parsable ${SBATCH_EXTRA:-} --array="0-$((shards - 1))" --output="$out/slurm/sweep-%A_%a.out" \
  "$here/sweep-array.sbatch" "$scene" "$out" "$@")
array=${array%%;*}  # --parsable prints "jobid[;cluster]"
# shellcheck disable=SC2086
merge=$(sbatch --parsable ${SBATCH_EXTRA:-} --dependency="afterok:$array" --kill-on-invalid-dep=yes \
  --output="$out/slurm/merge-%j.out" "$here/sweep-merge.sbatch" "$scene" "$out" "$@")
echo "${array} ${merge%%;*}"
