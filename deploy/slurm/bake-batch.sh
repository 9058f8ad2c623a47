#!/bin/bash
# One shard of a batch of bakes, as one task of a Slurm array job (docs/cluster.md):
#
#   sbatch --array=0-7 deploy/slurm/bake-batch.sh 8 hdris.txt /shared/baked --size 256
#
# Arguments: N, the number of shards (fixed for the batch, so that a task resubmitted alone,
# `sbatch --array=5 ...`, bakes the same share), the list of inputs (`ibl bake --list`: one path
# per line, relative to the job's working directory), the batch's output directory (on a file
# system every node sees: each input is baked into OUTDIR/<name>/), then any options of
# `ibl bake` (the same for every task). Task K bakes the inputs whose index in the list is K
# modulo N (`ibl bake --shard K/N`), with as many threads as the task has CPUs. A task
# resubmitted alone needs `--force` among the options: the inputs it baked before it failed left
# non-empty OUTDIR/<name>/ directories, which a bake refuses to overwrite without it.
#
# Environment: IBL, the command to run (default: ibl on the PATH).
# Test hook: IBL_FAIL_TASK=K makes task K exit with status 1 before running ibl.
#SBATCH --job-name=ibl-bake-batch
#SBATCH --cpus-per-task=4
#SBATCH --output=ibl-bake-batch-%A_%a.out
set -euo pipefail

if [ $# -lt 3 ]; then
  echo "usage: sbatch --array=0-<N-1> $0 N LIST OUTDIR [ibl bake options]" >&2
  exit 2
fi
shards=$1 list=$2 outdir=$3
shift 3
task=${SLURM_ARRAY_TASK_ID:?not a task of a Slurm array job (sbatch --array)}

if [ -n "${IBL_FAIL_TASK:-}" ] && [ "$IBL_FAIL_TASK" = "$task" ]; then
  echo "bake-batch.sh: task $task fails on purpose (IBL_FAIL_TASK=$IBL_FAIL_TASK)" >&2
  exit 1
fi

threads=()
[ -n "${SLURM_CPUS_PER_TASK:-}" ] && threads=(--threads "$SLURM_CPUS_PER_TASK")
exec "${IBL:-ibl}" "${threads[@]}" bake --list "$list" -o "$outdir" --shard "$task/$shards" "$@"
