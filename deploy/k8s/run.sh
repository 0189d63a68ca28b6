#!/usr/bin/env bash
# Runs a sharded cityspec build on Kubernetes: the spec as a ConfigMap, the cache on a
# ReadWriteMany volume, the shared stages, the Indexed Job of shards, then the merge.
# Kubernetes has no job dependencies, so this script waits for each Job in turn.
#
#   deploy/k8s/run.sh specs/day.toml
#
# The spec must name no input files (a generated layout, the built-in facades), or they
# must be added to the ConfigMap beside it. Change `completions`, `parallelism` and
# CITYSPEC_SHARD_COUNT together in shards-job.yaml.
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
spec="${1:?usage: run.sh SPEC}"
kubectl apply -f "$here/cache-pvc.yaml"
kubectl create configmap cityspec-spec --from-file=spec.toml="$spec" \
  --dry-run=client -o yaml | kubectl apply -f -
for job in city shards merge; do
  kubectl delete job "cityspec-$job" --ignore-not-found
  kubectl apply -f "$here/$job-job.yaml"
  kubectl wait --for=condition=complete --timeout=24h "job/cityspec-$job"
done
