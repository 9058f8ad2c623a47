#!/bin/bash
# One shard of a grid of light probes, as one task of a Slurm array job (docs/cluster.md):
#
#   sbatch --array=0-15 deploy/slurm/probe-grid.sh 16 level.glb /shared/level_probes \
#     --grid 16,4,16 --bounds -40,0,-40,40,10,40 --size 128 --spp 64
#
# then, once every task has succeeded, `ibl probe --merge /shared/level_probes`.
#
# Arguments: N, the number of shards (fixed for the grid, so that a task resubmitted alone,
# `sbatch --array=5 ...`, captures the same share: $SLURM_ARRAY_TASK_COUNT would then be 1),
# the scene, the grid's directory (on a file system every node sees), then any options of
# `ibl probe` (the same for every task). Task K captures the probes whose index is K modulo N
# (`ibl probe --shard K/N`), with as many threads as the task has CPUs.
#
# Environment: IBL, the command to run (default: ibl on the PATH).
# Test hook: IBL_FAIL_TASK=K makes task K exit with status 1 before running ibl, as a node that
# fails would (scripts/cluster.sh tests the merge's report and the resubmission with it).
#SBATCH --job-name=ibl-probe-grid
#SBATCH --cpus-per-task=16
#SBATCH --output=ibl-probe-grid-%A_%a.out
set -euo pipefail

if [ $# -lt 3 ]; then
  echo "usage: sbatch --array=0-<N-1> $0 N SCENE OUTDIR [ibl probe options]" >&2
  exit 2
fi
shards=$1 scene=$2 outdir=$3
shift 3
task=${SLURM_ARRAY_TASK_ID:?not a task of a Slurm array job (sbatch --array)}

if [ -n "${IBL_FAIL_TASK:-}" ] && [ "$IBL_FAIL_TASK" = "$task" ]; then
  echo "probe-grid.sh: task $task fails on purpose (IBL_FAIL_TASK=$IBL_FAIL_TASK)" >&2
  exit 1
fi

threads=()
[ -n "${SLURM_CPUS_PER_TASK:-}" ] && threads=(--threads "$SLURM_CPUS_PER_TASK")
exec "${IBL:-ibl}" "${threads[@]}" probe "$scene" -o "$outdir" --shard "$task/$shards" "$@"
