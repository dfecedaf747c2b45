#!/bin/bash
# Checks that a configuration of a synthesis report (synth.sh) was placed and routed on every
# seed at its board's clock, and that its bitstream was written.
#
#   constraints/flow/check_routed.sh REPORT.json CONFIG CLOCK_MHZ
set -euo pipefail
report=${1:?usage: check_routed.sh REPORT.json CONFIG CLOCK_MHZ}
config=${2:?usage: check_routed.sh REPORT.json CONFIG CLOCK_MHZ}
clock=${3:?usage: check_routed.sh REPORT.json CONFIG CLOCK_MHZ}
entry=$(grep -E "^ *\"$config\":" "$report") || { echo "check_routed.sh: $report: no configuration $config" >&2; exit 1; }
field() { echo "$entry" | grep -oE "\"$1\": [^,}]+" | awk '{ print $2 }' | tr -d '"'; }
[ "$(field fits)" = true ] || { echo "check_routed.sh: $config does not fit its device (or did not route)" >&2; exit 1; }
worst=$(field fmax_worst_mhz)
awk -v w="$worst" -v c="$clock" 'BEGIN { exit !(w != "null" && w >= c) }' ||
  { echo "check_routed.sh: $config: the worst seed's routed Fmax is $worst MHz, below the $clock MHz clock" >&2; exit 1; }
bitstream=$(field bitstream)
[ -s "$bitstream" ] || { echo "check_routed.sh: $config: no bitstream at $bitstream" >&2; exit 1; }
echo "check_routed.sh: $config routed on every seed, worst $worst MHz (median $(field fmax_mhz)) against $clock MHz; bitstream $bitstream ($(stat -c %s "$bitstream") bytes)"
