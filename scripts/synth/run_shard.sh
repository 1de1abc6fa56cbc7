#!/usr/bin/env bash
# One shard of a large synthetic data set: the task a Slurm job array or a Kubernetes
# indexed Job runs once per index. Every image is a pure function of (seed, image
# index), so the shards are disjoint and `flexsight synth merge` joins them into the
# data set one machine would have written (see docs/synth.md, "Scale-out").
#
#   SHARD_INDEX  this task's shard, 0..SHARDS-1 (default: SLURM_ARRAY_TASK_ID, then
#                JOB_COMPLETION_INDEX, the variables Slurm and Kubernetes set)
#   SHARDS       number of shards (default: SLURM_ARRAY_TASK_COUNT)
#   COUNT        images in the whole data set          SEED  its seed (default 1)
#   OUT          folder of the shards: this one writes OUT/shard-IIIII
#   MODE         full (default) or semi;  SYNTH_ARGS  more options for flexsight synth
#   FLEXSIGHT    the executable (default: build/flexsight beside this script)
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
index="${SHARD_INDEX:-${SLURM_ARRAY_TASK_ID:-${JOB_COMPLETION_INDEX:-}}}"
shards="${SHARDS:-${SLURM_ARRAY_TASK_COUNT:-}}"
: "${index:?set SHARD_INDEX (or run under a Slurm array / Kubernetes indexed Job)}"
: "${shards:?set SHARDS, the number of shards}"
: "${COUNT:?set COUNT, the number of images of the whole data set}"
: "${OUT:?set OUT, the folder the shards are written into}"
flexsight="${FLEXSIGHT:-$here/../../build/flexsight}"
mkdir -p "$OUT"
# --overwrite: a task that is retried after a failure writes its shard again from the
# start (the shard's folder appears only when it is complete).
# shellcheck disable=SC2086
exec "$flexsight" synth "${MODE:-full}" --count "$COUNT" --seed "${SEED:-1}" \
  --shard "$index/$shards" -o "$OUT/shard-$(printf %05d "$index")" --overwrite ${SYNTH_ARGS:-}
