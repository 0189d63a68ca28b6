#!/usr/bin/env bash
# Runs a sharded cityspec build on Kubernetes: the spec and every file it reads as one
# `cityspec pack` archive in a ConfigMap, the cache on a ReadWriteMany volume, the shared
# stages, the Indexed Job of shards, then the merge. Kubernetes has no job dependencies,
# so this script waits for each Job in turn.
#
#   docker build -f deploy/Dockerfile -t cityspec:0.1.0 .   # the image the jobs run
#   deploy/k8s/run.sh specs/day.toml
#
# `cityspec` must be on this machine's PATH (to pack the spec). A ConfigMap holds at most
# 1 MiB: a spec whose files are larger (a big facade folder) needs them on a volume.
# Change `completions`, `parallelism` and CITYSPEC_SHARD_COUNT together in
# shards-job.yaml.
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
spec="${1:?usage: run.sh SPEC}"
kubectl apply -f "$here/cache-pvc.yaml"
packed="$(mktemp -d)"
trap 'rm -rf "$packed"' EXIT
# The archive names its spec in CITYSPEC_SPEC; the jobs unpack it and build that.
cityspec pack "$spec" -o "$packed/spec.tar"
kubectl create configmap cityspec-spec --from-file=spec.tar="$packed/spec.tar" \
  --dry-run=client -o yaml | kubectl apply -f -
for job in city shards merge; do
  kubectl delete job "cityspec-$job" --ignore-not-found
  kubectl apply -f "$here/$job-job.yaml"
  kubectl wait --for=condition=complete --timeout=24h "job/cityspec-$job"
done
