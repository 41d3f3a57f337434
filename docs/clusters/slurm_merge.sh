#!/bin/bash
# Merges the parts of `slurm_sweep.sh` into one table: every run once, each
# with the plan's values, or an error that names the part and the run.
#SBATCH --job-name=lpm-merge
#SBATCH --time=00:10:00
set -euo pipefail
source "${SLURM_SUBMIT_DIR:-.}/docs/clusters/sweep.env"
lpm "${SWEEP[@]}" --merge "$RESULTS"/part-*.parquet --out "$RESULTS/sweep.parquet"
