#!/usr/bin/env bash
# Submits a sharded cityspec build to Slurm: the shared stages once (the city, the
# camera paths' poses), an array of N shards after them, and the merge after the array.
#
#   CITYSPEC_CACHE=/shared/cityspec-cache deploy/slurm/submit.sh specs/day.toml 16 [OUT]
#
# Prints the merge's job id. Every job reads the same spec file and cache folder.
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
spec="${1:?usage: submit.sh SPEC SHARDS [OUT]}"
shards="${2:?usage: submit.sh SPEC SHARDS [OUT]}"
out="${3:-out}"
: "${CITYSPEC_CACHE:?set CITYSPEC_CACHE to a cache folder on the shared file system}"
export CITYSPEC_CACHE
city=$(sbatch --parsable --job-name=cityspec-city --output=cityspec-city-%j.log \
  --wrap "${CITYSPEC:-cityspec} build --cache '$CITYSPEC_CACHE' --stage city '$spec'")
array=$(sbatch --parsable --dependency="afterok:$city" --array="0-$((shards - 1))" \
  "$here/shards.sbatch" "$spec")
sbatch --parsable --dependency="afterok:$array" "$here/merge.sbatch" "$spec" "$out"
