#!/usr/bin/env bash
# README "Scaling out": one -j1 build of a 200-frame street path against 2 -j1 shards at
# once sharing one cache, then the merge; wall and CPU seconds of each (`time -p`), and
# the two output folders compared byte for byte. Run it on a quiet machine:
#
#   cargo build --release && benches/shards.sh target/release/cityspec
set -euo pipefail
B="$(realpath "${1:?usage: benches/shards.sh CITYSPEC}")"
repo="$(cd "$(dirname "$0")/.." && pwd)"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
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
