#!/usr/bin/env bash
# The Slurm path for real: a one-node Slurm cluster on localhost (Debian's slurm-wlm and
# munge), deploy/slurm/submit.sh submits the shared stages, an array of shards and the
# dependent merge, and the merged output folder must equal a one-machine build's, byte
# for byte. Needs root (it starts munged, slurmctld and slurmd) and apt-get when Slurm is
# missing.
#
#   tests/external/slurm.sh path/to/cityspec SPEC [SHARDS]
set -euo pipefail
cityspec="$(realpath "${1:?usage: slurm.sh CITYSPEC SPEC [SHARDS]}")"
spec="$(realpath "${2:?usage: slurm.sh CITYSPEC SPEC [SHARDS]}")"
shards="${3:-3}"
repo="$(cd "$(dirname "$0")/../.." && pwd)"
if ! command -v slurmctld >/dev/null || ! command -v munged >/dev/null; then
  DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends \
    slurm-wlm munge >/dev/null
fi
work="$(mktemp -d)"
cleanup() {
  for pid in "$work"/*.pid; do
    [ -e "$pid" ] && kill "$(cat "$pid")" 2>/dev/null || true
  done
  sleep 1
  rm -rf "$work" 2>/dev/null || true
}
trap cleanup EXIT
mkdir -p "$work/state" "$work/spool" "$work/munge" "$work/run"
# munge: its own key, socket and pid file, so it does not touch a system munged.
dd if=/dev/urandom of="$work/munge/key" bs=1024 count=1 status=none
chmod 700 "$work/munge"; chmod 400 "$work/munge/key"
munged --force --key-file="$work/munge/key" --socket="$work/munge/socket" \
  --pid-file="$work/munged.pid" --log-file="$work/munge/log" --seed-file="$work/munge/seed"
host="$(hostname -s)"
cat > "$work/slurm.conf" <<CONF
ClusterName=cityspec-ci
SlurmctldHost=$host
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
AuthInfo=socket=$work/munge/socket
CredType=cred/munge
StateSaveLocation=$work/state
SlurmdSpoolDir=$work/spool
SlurmctldPidFile=$work/slurmctld.pid
SlurmdPidFile=$work/slurmd.pid
SlurmctldLogFile=$work/slurmctld.log
SlurmdLogFile=$work/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SchedulerType=sched/builtin
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
MpiDefault=none
ReturnToService=2
JobCompType=jobcomp/none
AccountingStorageType=accounting_storage/none
NodeName=$host CPUs=$(nproc) RealMemory=$(awk '/MemTotal/ {print int($2 / 1024)}' /proc/meminfo) State=UNKNOWN
PartitionName=ci Nodes=$host Default=YES MaxTime=INFINITE State=UP
CONF
export SLURM_CONF="$work/slurm.conf"
slurmctld
slurmd
for _ in $(seq 1 30); do
  sinfo -h -o %t 2>/dev/null | grep -q idle && break
  sleep 1
done
sinfo
cd "$work/run"
export CITYSPEC="$cityspec" CITYSPEC_CACHE="$work/cache"
merge=$("$repo/deploy/slurm/submit.sh" "$spec" "$shards" "$work/run/out")
echo "submitted; the merge is job $merge"
for _ in $(seq 1 600); do
  state=$(scontrol show job "$merge" 2>/dev/null | grep -o 'JobState=[A-Z_]*' || true)
  case "$state" in
    JobState=COMPLETED) break ;;
    JobState=FAILED|JobState=CANCELLED|JobState=TIMEOUT|JobState=NODE_FAIL|JobState=OUT_OF_MEMORY)
      cat "$work"/run/*.log; echo "the merge ended $state"; exit 1 ;;
  esac
  sleep 1
done
[ "$state" = JobState=COMPLETED ] || { cat "$work"/run/*.log; echo "timed out: $state"; exit 1; }
grep -h "shard " "$work"/run/cityspec-shard-*.log
"$cityspec" build -q --cache "$work/one-cache" --out "$work/one" "$spec"
name="$(basename "$(ls -d "$work"/one/*/ | head -1)")"
diff -r "$work/one/$name" "$work/run/out/$name"
echo "slurm: $shards shards + merge give the bytes of one machine ($(wc -l < "$work/one/$name/manifest.json") manifest lines)"
