#!/bin/bash
# Replays recordings in real time through each backend and prints, as a markdown table, the
# latency from arrival to label (p50, p99) at 1x, the highest speed factor (1, 2, 4, ...) at
# which the backend keeps up (no event dropped with a live buffer of 65,536 events, and a p99
# latency under 100 ms), and the backend's rate when it is not paced at all.
#
#   tests/bench/realtime_backends.sh [BUILD_DIR] [RECORDING ...]
#
# BACKENDS="rtl" (a list) measures those backends only; all three by default.
# Default recordings: every file in ../shared/data/real.
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
build=${1:-$root/build}
shift || true
recordings=("$@")
if [ ${#recordings[@]} -eq 0 ]; then
  for f in "$root"/../shared/data/real/*.{aedat4,raw,dat}; do [ -e "$f" ] && recordings+=("$f"); done
fi
evms=$build/bin/evms
max_speed=256

run() {  # run FILE BACKEND SPEED: prints "dropped p50 p99 events_per_s"
  local out
  out=$("$evms" run "$1" --backend "$2" --realtime --speed "$3" --live-buffer 65536 --quiet)
  local dropped p50 p99 rate
  dropped=$(sed -n 's/^live *\([0-9,]*\) events dropped.*/\1/p' <<<"$out" | tr -d ,)
  p50=$(sed -n 's/^latency .*p50 \([0-9]*\) us.*/\1/p' <<<"$out")
  p99=$(sed -n 's/^latency .*p99 \([0-9]*\) us.*/\1/p' <<<"$out")
  rate=$(sed -n 's/^throughput *\([0-9.]* [kM]*\)events\/s.*/\1/p' <<<"$out")
  echo "$dropped $p50 $p99 $rate"
}

echo "| recording | input rate | backend | unpaced events/s | p50 at 1x | p99 at 1x | dropped at 1x | highest speed kept up | p50 there | p99 there |"
echo "|---|---|---|---|---|---|---|---|---|---|"
for f in "${recordings[@]}"; do
  input=$("$evms" info "$f" | sed -n 's/.*mean rate *\([0-9.]* [kM]*\)events\/s.*/\1/p')
  for backend in ${BACKENDS:-golden fixed rtl}; do
    unpaced=$("$evms" run "$f" --backend $backend --quiet | sed -n 's/^throughput *\([0-9.]* [kM]*\)events\/s.*/\1/p')
    read -r d1 a1 b1 r1 < <(run "$f" $backend 1)
    best=0 bp50=- bp99=- brate=-
    speed=1
    while [ $speed -le $max_speed ]; do
      read -r d p50 p99 rate < <(run "$f" $backend $speed)
      { [ "$d" != 0 ] || [ "$p99" -ge 100000 ]; } && break
      best=$speed bp50=$p50 bp99=$p99 brate=$rate
      speed=$((speed * 2))
    done
    [ $best = 0 ] && best="below 1x"
    [ "$best" = $max_speed ] && best=">= ${max_speed}x (limit of the sweep)"
    printf '| %s | %s | %s | %s | %s us | %s us | %s | %s | %s us | %s us |\n' "$(basename "$f")" "$input" $backend "$unpaced" \
      "$a1" "$b1" "$d1" "$best$( [[ $best =~ ^[0-9]+$ ]] && echo x)" "$bp50" "$bp99"
  done
done
