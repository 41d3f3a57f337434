#!/bin/bash
# A sweep of the paper scenario as a Slurm array job: each task runs its
# shard; `slurm_merge.sh`, submitted with a dependency, checks the parts and
# writes the table one full run would have written. Submit both from the
# repository root:
#
#   jobid=$(sbatch --parsable docs/clusters/slurm_sweep.sh)
#   sbatch --dependency=afterok:$jobid docs/clusters/slurm_merge.sh
#
# `lpm "${SWEEP[@]}" --plan` prints the number of runs and a suggested
# number of tasks for --array.
#SBATCH --job-name=lpm-sweep
#SBATCH --array=1-16
#SBATCH --cpus-per-task=4
#SBATCH --time=00:30:00
set -euo pipefail
# Slurm runs a copy of this script: find the sweep beside the original.
source "${SLURM_SUBMIT_DIR:-.}/docs/clusters/sweep.env"
mkdir -p "$RESULTS"
lpm "${SWEEP[@]}" --shard auto --threads "${SLURM_CPUS_PER_TASK:-1}" --quiet \
    --out "$RESULTS/part-${SLURM_ARRAY_TASK_ID}.parquet"
