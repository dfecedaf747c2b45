#!/bin/bash
# Compares a synthesis report (synth.sh) with the committed baseline: prints every resource
# and the logic delay of the longest path beside its baseline, and fails when a resource grew by
# more than the tolerance (default 2 %), the logic delay by more than its own (default 5 %),
# when a configuration that fitted its device no longer does, or when an Arty configuration that
# fitted takes more than its budget of the XC7A35T's LUTs (devices.sh: 80 %), which a growth
# within the tolerance can pass.
#
# The logic delay has the wider tolerance because Yosys's mapping moves it by several percent
# for changes that touch no path: a configuration register that the iCEBreaker build never reads
# moved its longest path from 19.86 to 20.62 ns (+3.8 %), and to other blocks. The routed clock
# that matters is check_routed.sh's to judge.
#
#   constraints/flow/compare.sh REPORT.json [BASELINE.json] [TOLERANCE_PERCENT] [LOGIC_TOLERANCE_PERCENT]
#
# After a change that is worth its area, copy the report over baseline.json in the same commit.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
source "$here/devices.sh"
report=${1:?usage: compare.sh REPORT.json [BASELINE.json] [TOLERANCE_PERCENT] [LOGIC_TOLERANCE_PERCENT]}
baseline=${2:-$here/baseline.json}
resource_tolerance=${3:-2}
logic_tolerance=${4:-5}

field() {  # field FILE CONFIG KEY
  grep -E "^ *\"$2\":" "$1" | grep -oE "\"$3\": [^,}]+" | awk '{ print $2 }'
}

status=0
printf '%-10s %-8s %10s %10s %8s\n' config resource baseline now change
for config in $(grep -oE '^ *"[a-z0-9_]+":' "$report" | tr -d ' ":'); do
  if ! grep -qE "^ *\"$config\":" "$baseline"; then
    echo "$config: not in the baseline $baseline" >&2
    status=1
    continue
  fi
  for key in lut ff dsp bram spram logic_ns fmax_mhz; do
    was=$(field "$baseline" "$config" $key)
    now=$(field "$report" "$config" $key)
    change=$(awk -v a="$was" -v b="$now" 'BEGIN { if (a == "null" || b == "null") print "-"; else if (a == 0) print (b == 0 ? "0.0%" : "new"); else printf "%+.1f%%", 100 * (b - a) / a }')
    printf '%-10s %-8s %10s %10s %8s\n' "$config" $key "$was" "$now" "$change"
    tolerance=$([ $key = logic_ns ] && echo "$logic_tolerance" || echo "$resource_tolerance")
    if [ $key != fmax_mhz ] && awk -v a="$was" -v b="$now" -v t="$tolerance" -v k=$key 'BEGIN { exit !(b > a * (1 + t / 100) + (k == "logic_ns" ? 0 : 0.5)) }'; then
      echo "compare.sh: $config $key grew from $was to $now, more than $tolerance %" >&2
      status=1
    fi
  done
  if [ "$(field "$baseline" "$config" fits)" = true ] && [ "$(field "$report" "$config" fits)" != true ]; then
    echo "compare.sh: $config no longer fits its device" >&2
    status=1
  fi
  budget=$((capacity[xc7_lut] * xc7_lut_budget_percent / 100))
  if [[ $config == xc7_* ]] && [ "$(field "$baseline" "$config" fits)" = true ] && [ "$(field "$report" "$config" lut)" -gt $budget ]; then
    echo "compare.sh: $config takes $(field "$report" "$config" lut) LUTs, above its budget of $budget ($xc7_lut_budget_percent % of the XC7A35T's ${capacity[xc7_lut]})" >&2
    status=1
  fi
done
exit $status
