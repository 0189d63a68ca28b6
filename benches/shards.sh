#!/usr/bin/env bash
# docs/scaling.md, "Scaling out": one -j1 build of a 200-frame street path against 2 -j1 shards at
# once sharing one cache, then the merge; wall and CPU seconds of each (`time -p`), and
# the two output folders compared byte for byte. Then, when moto is installed (MOTO_SERVER,
# or moto_server on PATH: pip install 'moto[server]'), the S3 overhead: the same -j1 build
# with its cache on a local S3 server against the local folder, cold and warm (a rebuild
# into a new folder, which reads and verifies every object). Run it on a quiet machine:
#
#   cargo build --release && MOTO_SERVER=venv/bin/moto_server benches/shards.sh target/release/cityspec
set -euo pipefail
B="$(realpath "${1:?usage: benches/shards.sh CITYSPEC}")"
repo="$(cd "$(dirname "$0")/.." && pwd)"
work="$(mktemp -d)"
moto=""
trap 'rm -rf "$work"; [ -z "$moto" ] || kill "$moto"' EXIT
cp -r "$repo/specs" "$repo/assets" "$work/"
cd "$work"
# day.toml with its street path at 200 frames and no aerial path.
sed -e 's/^name = "day"/name = "day200"/' -e 's/^frames = 100/frames = 200/' specs/day.toml |
  awk '/^\[\[cameras\]\] +# an overview/ {skip = 1} /^\[lighting\]/ {skip = 0} !skip' \
  > specs/day200.toml
t() { { time -p "$@" >/dev/null 2>&1; } 2>&1 | awk '{printf "%s %s  ", $1, $2}'; echo; }
echo "load before: $(cut -d' ' -f1-3 /proc/loadavg)"
echo "city (--stage city): $(t "$B" build -j1 --stage city --cache base specs/day200.toml)"
cp -a base c1
cp -a base c2
echo "one -j1:            $(t "$B" build -j1 --cache c1 --out o1 specs/day200.toml)"
start=$(date +%s.%N)
t "$B" build -j1 --cache c2 --shard 0/2 specs/day200.toml > s0 &
t "$B" build -j1 --cache c2 --shard 1/2 specs/day200.toml > s1 &
wait
echo "2 shards -j1:       wall $(echo "$(date +%s.%N) - $start" | bc)  [$(cat s0)] [$(cat s1)]"
echo "merge -j1:          $(t "$B" build -j1 --cache c2 --out o2 specs/day200.toml)"
diff -r o1/day200 o2/day200 && echo "identical outputs"
echo "load after: $(cut -d' ' -f1-3 /proc/loadavg)"

moto_server="${MOTO_SERVER:-$(command -v moto_server || true)}"
if [ -z "$moto_server" ]; then
  echo "S3 overhead: skipped (no moto_server; set MOTO_SERVER)"
  exit 0
fi
port=$((20000 + RANDOM % 20000))
"$moto_server" -H 127.0.0.1 -p "$port" > moto.log 2>&1 &
moto=$!
for _ in $(seq 100); do curl -sf -o /dev/null "http://127.0.0.1:$port/" && break; sleep 0.2; done
curl -sf -X PUT -o /dev/null "http://127.0.0.1:$port/bench"
export AWS_ENDPOINT_URL="http://127.0.0.1:$port" AWS_ALLOW_HTTP=true AWS_REGION=us-east-1 \
  AWS_ACCESS_KEY_ID=bench AWS_SECRET_ACCESS_KEY=bench
echo "cold, local cache:  $(t "$B" build -j1 --cache l --out ol specs/day200.toml)"
echo "cold, S3 cache:     $(t "$B" build -j1 --cache s3://bench/c --out os specs/day200.toml)"
echo "warm, local cache:  $(t "$B" build -j1 --cache l --out ol2 specs/day200.toml)"
echo "warm, S3 cache:     $(t "$B" build -j1 --cache s3://bench/c --out os2 specs/day200.toml)"
diff -r ol/day200 os/day200 && diff -r ol/day200 os2/day200 && echo "identical outputs"
echo "objects: $(find l/objects -type f | wc -l), $(du -sm l/objects | cut -f1) MiB"
