#!/bin/bash
# Submits a stiction Monte Carlo study to Slurm: one array task per shard, then a merge job that
# starts only when every shard succeeded.
#
#   scripts/slurm/submit-study.sh SCENARIO SAMPLES SHARDS OUT [SEED [extra study flags...]]
#
# e.g. scripts/slurm/submit-study.sh scenarios/tas2000.json 1000000 50 /scratch/$USER/tas 1
# Resources per task are in study-shard.sbatch (#SBATCH lines); override with SBATCH_* variables
# or edit them (docs/cluster.md explains the sizing).
set -euo pipefail
if [ $# -lt 4 ]; then
    sed -n '2,9p' "$0"
    exit 2
fi
here="$(cd "$(dirname "$0")" && pwd)"
export STUDY_SCENARIO="$1" STUDY_SAMPLES="$2" STUDY_SHARDS="$3" STUDY_OUT="$4" STUDY_SEED="${5:-1}"
shift 4
if [ $# -gt 0 ]; then shift; fi
# The extra study flags stay a list of words, each as given ("$@", never "$*"): sbatch passes the
# arguments after the script to it, so `--set "surface.summit_sd=20 nm"` arrives as two words.
mkdir -p "$STUDY_OUT/logs"
array=$(sbatch --parsable --export=ALL --array="0-$((STUDY_SHARDS - 1))" \
    --output="$STUDY_OUT/logs/shard-%a.out" "$here/study-shard.sbatch" "$@")
array="${array%%;*}"
merge=$(sbatch --parsable --export=ALL --dependency="afterok:$array" \
    --output="$STUDY_OUT/logs/merge.out" "$here/study-merge.sbatch" "$@")
echo "submitted shards as array job $array and the merge as job $merge; results in $STUDY_OUT/merged"
