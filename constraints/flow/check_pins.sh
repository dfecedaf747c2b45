#!/bin/bash
# Checks a board's constraint file against its top's ports, as Yosys reads the top:
#  - every bit of every port has a pin, and no bit two;
#  - every name the file constrains is a bit of a port;
#  - no pin carries two bits;
#  - in an .xdc, every port bit has an I/O standard, and with CLOCK_HZ the clock constrained on
#    the port CLK has the period of the build's clock;
#  - every active-low input (a name ending in _N: the button, the sensor's request) has the
#    FPGA's pull-up, so that it idles high with nothing connected: a floating AER request line
#    would take noise for the sensor's handshake and feed the core events no sensor sent.
# nextpnr-ice40 refuses a port without a pin, but the .pcf's -nowarn lets a stale name pass, and
# Vivado, which the Arty's place and route needs (docs/rtl.md), only warns of either. Each error
# is one line naming the file and the line.
#
#   constraints/flow/check_pins.sh TOP CONSTRAINTS_FILE [CLOCK_HZ]
set -euo pipefail
usage="usage: check_pins.sh TOP CONSTRAINTS_FILE [CLOCK_HZ]"
top=${1:?$usage}
file=${2:?$usage}
clock_hz=${3:-}
root=$(cd "$(dirname "$0")/../.." && pwd)
[ -r "$file" ] || { echo "check_pins.sh: $file: cannot read the constraint file" >&2; exit 1; }
case "$file" in
  *.pcf) kind=pcf ;;
  *.xdc) kind=xdc ;;
  *) echo "check_pins.sh: $file: not a .pcf or an .xdc" >&2; exit 1 ;;
esac
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

# The top alone: its ports need neither the board below it nor the iCE40's cells it instantiates.
(cd "$root/rtl/generated" &&
  yosys -q -p "read_verilog -lib +/ice40/cells_sim.v; read_verilog -sv -DSYNTHESIS -I. -I../board -I../common ../board/$top.sv;
               proc; select $top; write_verilog -selected -noattr $tmp/top.v") >"$tmp/yosys.log" 2>&1 ||
  { echo "check_pins.sh: $top: Yosys could not read the top (rtl/board/$top.sv):" >&2; cat "$tmp/yosys.log" >&2; exit 1; }
# One line a port bit: NAME, or NAME[i] for each bit of a vector.
awk '/^ *(input|output|inout) / {
       sub(/;.*/, ""); name = $NF
       if ($2 ~ /^\[/) { split(substr($2, 2, length($2) - 2), r, ":"); lo = r[1] < r[2] ? r[1] : r[2]; hi = r[1] < r[2] ? r[2] : r[1]
                         for (i = lo; i <= hi; ++i) print name "[" i "]" }
       else print name
     }' "$tmp/top.v" | sort >"$tmp/ports"
awk '/^ *input / { sub(/;.*/, ""); if ($NF ~ /_N$/) print $NF }' "$tmp/top.v" | sort >"$tmp/active_low_inputs"
[ -s "$tmp/ports" ] || { echo "check_pins.sh: $top: no ports read" >&2; exit 1; }

# The file's constraints, one line each: LINE NAME PIN, LINE NAME for each name with a pull-up,
# and for an .xdc LINE NAME STANDARD and the clock's LINE NAME PERIOD.
if [ $kind = pcf ]; then
  # set_io [-nowarn] [-pullup yes|no] [-pullup_resistor R] NAME PIN (the .pcf syntax of nextpnr-ice40's documentation).
  awk -v pullups="$tmp/pullups" '{ sub(/#.*/, "") }
       $1 == "set_io" { n = 0; a[1] = a[2] = ""; pullup = 0
                        for (i = 2; i <= NF; ++i) {
                          if ($i == "-pullup") pullup = $(++i) == "yes"
                          else if ($i == "-pullup_resistor") ++i
                          else if ($i !~ /^-/) a[++n] = $i
                        }
                        print FNR, a[1], a[2]
                        if (pullup) print FNR, a[1] > pullups }' "$file" >"$tmp/pins"
  touch "$tmp/pullups"
else
  # Each line that names a port: its PACKAGE_PIN, IOSTANDARD and create_clock -period, into three lists.
  awk -v pins="$tmp/pins" -v standards="$tmp/standards" -v clocks="$tmp/clocks" -v pullups="$tmp/pullups" '
    function after(key,   v) { if (!match($0, key " +[^ }]+")) return ""; v = substr($0, RSTART, RLENGTH); sub(key " +", "", v); return v }
    { sub(/^ *#.*/, "") }
    match($0, /get_ports *[{][^}]*[}]/) {
      list = substr($0, RSTART, RLENGTH); sub(/get_ports *[{]/, "", list); sub(/[}]$/, "", list)
      n = split(list, names, " ")
      for (i = 1; i <= n; ++i) {
        if (after("PACKAGE_PIN") != "") print FNR, names[i], after("PACKAGE_PIN") > pins
        if (after("IOSTANDARD") != "") print FNR, names[i] > standards
        if (toupper(after("PULLUP")) == "TRUE") print FNR, names[i] > pullups
        if (/create_clock/) print FNR, names[i], after("-period") > clocks
      }
    }' "$file"
  touch "$tmp/pins" "$tmp/standards" "$tmp/clocks" "$tmp/pullups"
fi

errors=0
fail() { echo "check_pins.sh: $*" >&2; errors=$((errors + 1)); }
while read -r line name pin; do
  grep -qxF "$name" "$tmp/ports" || fail "$file:$line: $name is not a port of $top (rtl/board/$top.sv)"
  [ -n "$pin" ] || fail "$file:$line: $name has no pin"
done <"$tmp/pins"
while read -r port; do
  n=$(awk -v p="$port" '$2 == p' "$tmp/pins" | wc -l)
  [ "$n" -eq 1 ] || fail "$file: $top's port $port has $n pins (one wanted)"
  if [ $kind = xdc ]; then
    awk -v p="$port" '$2 == p { f = 1 } END { exit !f }' "$tmp/standards" || fail "$file: $top's port $port has no IOSTANDARD"
  fi
done <"$tmp/ports"
while read -r port; do
  awk -v p="$port" '$2 == p { f = 1 } END { exit !f }' "$tmp/pullups" ||
    fail "$file: $top's active-low input $port has no pull-up (it floats with nothing connected)"
done <"$tmp/active_low_inputs"
awk '{ if ($3 in first) printf "%s:%d: pin %s carries %s and, on line %d, %s\n", FILENAME, $1, $3, $2, first[$3], name[$3]
       else { first[$3] = $1; name[$3] = $2 } }' "$tmp/pins" | sed "s|^$tmp/pins|$file|" >"$tmp/twice"
while read -r message; do fail "$message"; done <"$tmp/twice"
if [ $kind = xdc ] && [ -n "$clock_hz" ]; then
  read -r line name period < <(awk '$2 == "CLK"' "$tmp/clocks") || true
  if [ -z "${period:-}" ]; then
    fail "$file: no create_clock on the port CLK"
  else
    awk -v p="$period" -v hz="$clock_hz" 'BEGIN { want = 1e9 / hz; exit !(p - want < 1e-3 && want - p < 1e-3) }' ||
      fail "$file:$line: the clock's period is $period ns, the build's clock $clock_hz Hz asks $(awk -v hz="$clock_hz" 'BEGIN { printf "%.3f", 1e9 / hz }') ns"
  fi
fi
[ $errors -eq 0 ] || exit 1
echo "check_pins.sh: $file: each of $top's $(wc -l <"$tmp/ports") port bits on a pin of its own, its $(wc -l <"$tmp/active_low_inputs") active-low inputs pulled up"
