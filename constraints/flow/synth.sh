#!/bin/bash
# Synthesizes the board tops with Yosys (synth_ice40 for the iCEBreaker's iCE40 UP5K,
# synth_xilinx for the Arty's XC7A35T), places and routes the iCE40 ones that fit with
# nextpnr-ice40 over several seeds (constraints/icebreaker.pcf, the build's clock asked: 18 MHz,
# BoardClockHz of rtl/generated/evms_cfg_ice40.svh, made by the PLL of the 12 MHz oscillator), packs the
# best-routed seed's bitstream with icepack, and writes one JSON report: LUT, FF, DSP, BRAM and
# SPRAM use, the routed Fmax (median and worst over the seeds), the bitstream's path, and for
# every configuration the logic delay of its longest
# register-to-register path (Yosys sta with the cell delays of Yosys's own cell models, which
# on the XC7 include the DSP48E1's and block RAM's; no routing, so it is a lower bound on the
# clock period and 1000 / logic_ns an upper bound on Fmax; it also names the path's blocks and
# source lines).
# Both board builds hold the seeded path only, which has no lanes (the lane count is the
# Gaussian path's), so ice40_p1 is the iCEBreaker build (its core cut after the climbs,
# BoardCoreCut) and xc7_p8 the Arty build; the other lane counts build the same cores.
# ice40core_p1 is the iCEBreaker top with the whole ice40 core, which does not fit the UP5K: its
# figures say how far the core is from it.
#
#   constraints/flow/synth.sh [-j JOBS] [-s SEEDS] [-o REPORT.json] [-b] [CONFIG ...]
#
# CONFIG is ice40_p1 .. ice40_p8, ice40core_p1 .. ice40core_p8 or xc7_p1 .. xc7_p8 (default:
# ice40_p1, ice40core_p1 and xc7_p8).
# -b also synthesizes each configuration with the core's blocks kept apart (keep_hierarchy on
# the filter, intake, climbs core, serial climbs, mean shift, merge, seeded climbs, mode links, warm seeds, centroids,
# tracker, multiplier and reciprocal, those the build holds; the rest of the
# core and of the board top counted as theirs) and writes their resources to
# <work>/<config>/blocks.txt. Keeping them apart stops optimization across their ports, so
# their sum is a little above the flat figures of the report.
# compare.sh checks a report against baseline.json.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../.." && pwd)
jobs=2
seeds=5
out=$root/build/synth/report.json
blocks=false
while getopts "j:s:o:b" opt; do
  case $opt in
    j) jobs=$OPTARG ;;
    s) seeds=$OPTARG ;;
    o) out=$OPTARG ;;
    b) blocks=true ;;
    *) sed -n '2,/^set -euo/p' "$0" | sed '$d'; exit 2 ;;
  esac
done
shift $((OPTIND - 1))
out=$(realpath -m "$out")   # the runs work inside rtl/generated
configs=("$@")
[ ${#configs[@]} -eq 0 ] && configs=(ice40_p1 ice40core_p1 xc7_p8)
for tool in yosys nextpnr-ice40 icepack; do
  command -v $tool >/dev/null || { echo "synth.sh: $tool not found (apt install yosys nextpnr-ice40 fpga-icestorm)" >&2; exit 1; }
done

work=$(dirname "$out")/work
mkdir -p "$work"
sources=()
while read -r f; do sources+=("$root/rtl/$f"); done < <(cat "$root/rtl/core.f" "$root/rtl/board.f")
# The iCEBreaker build's clock in MHz (EVMS_BOARD_ice40: clock Hz, UART clocks a bit, ...).
ice40_mhz=$(sed -nE 's/^set\(EVMS_BOARD_ice40 ([0-9]+) .*/\1/p' "$root/rtl/generated/evms_cfg_ice40.cmake" | awk '{ print $1 / 1e6 }')
[ -n "$ice40_mhz" ] || { echo "synth.sh: rtl/generated/evms_cfg_ice40.cmake: no EVMS_BOARD_ice40 clock" >&2; exit 1; }

# The cell models with their specify delays, minus the asynchronous set/reset-to-Q arcs, which
# sta would otherwise chain into the reset tree (a reset is not a clocked path).
share=$(dirname "$(command -v yosys)")/../share/yosys
for family in xilinx ice40; do
  [ -f "$share/$family/cells_sim.v" ] || { echo "synth.sh: $share/$family/cells_sim.v not found (Yosys's cell models)" >&2; exit 1; }
  # written aside and renamed: another run of this script (a parallel test) may be reading it
  sed -E '/\((CLR|PRE|R|S) => Q\)/d' "$share/$family/cells_sim.v" > "$work/timing_$family.v.$$"
  mv -f "$work/timing_$family.v.$$" "$work/timing_$family.v"
done

# The iCE40 UP5K and the XC7A35T, for the "fits" verdict.
source "$here/devices.sh"

count() {  # count FILE SECTION CELL-REGEX: the sum of the matching cell counts of SECTION ("design",
           # the whole design, or a module's name as yosys stat -json spells it) in a yosys stat -json
  # (the key through the environment: awk -v would take the backslashes of escaped names as escapes)
  key="\"$2\": {" awk 'index($0, ENVIRON["key"]) { on = 1 } on { print } on && /^ *}/ { exit }' "$1" |
    { grep -oE "\"($3)\": [0-9]+" || true; } | awk '{ s += $2 } END { print s + 0 }'
}

resources() {  # resources FAMILY FILE SECTION: "LUT FF DSP BRAM SPRAM" of SECTION in a yosys stat -json
  local f=$2 m=$3
  if [ "$1" = ice40 ]; then
    echo "$(count "$f" "$m" SB_LUT4) $(count "$f" "$m" 'SB_DFF[A-Z]*') $(count "$f" "$m" SB_MAC16) $(count "$f" "$m" SB_RAM40_4K) $(count "$f" "$m" SB_SPRAM256KA)"
  else
    # LUTs as logic and as distributed RAM (a RAM64M is four LUTs); block RAM in 36 kb tiles.
    echo "$(( $(count "$f" "$m" 'LUT[1-6]') + 4 * $(count "$f" "$m" 'RAM64M|RAM32M') + 2 * $(count "$f" "$m" 'RAM64X1D|RAM32X1D') + $(count "$f" "$m" 'RAM64X1S|RAM32X1S|SRL16E|SRLC32E') ))" \
      "$(count "$f" "$m" 'FD[A-Z]*') $(count "$f" "$m" DSP48E1)" \
      "$(awk -v a="$(count "$f" "$m" RAMB36E1)" -v b="$(count "$f" "$m" RAMB18E1)" 'BEGIN { printf "%g", a + b / 2 }') 0"
  fi
}

run_config() {
  local name=$1 family=${1%_p*} lanes=${1#*_p} dir=$work/$1 top synth netlist timing cut=""
  mkdir -p "$dir"
  rm -f "$dir/stat.json" "$dir/sta.txt" "$dir/entry.json" "$dir"/*.asc "$dir"/*.bin   # a failed run must not leave an earlier run's figures
  if [ "$family" = ice40core ]; then
    family=ice40
    cut="-chparam CoreCutOverride 0"
  fi
  if [ "$family" = ice40 ]; then
    top=evms_icebreaker_top
    synth="synth_ice40 -dsp -spram -top $top"
    netlist="write_json $dir/netlist.json"   # for nextpnr
    # The PLL's model has no timing arcs, so sta would time nothing it clocks: for sta, its
    # output is an input of the design, as the oscillator's pin was.
    timing="read_verilog -D ICE40_U -lib -specify $work/timing_ice40.v; expose -input t:SB_PLL40_PAD %co:+[PLLOUTGLOBAL] w:* %i; delete t:SB_PLL40_PAD"
  else
    top=evms_arty_top
    synth="synth_xilinx -family xc7 -flatten -top $top"
    netlist=""
    timing="read_verilog -lib -specify $work/timing_xilinx.v"
  fi
  # yosys_on RUN SCRIPT: the top elaborated at this lane count, then SCRIPT; logs in $dir/RUN.*
  yosys_on() {
    # $readmemh paths in the generated headers are relative to rtl/generated.
    (cd "$root/rtl/generated" && yosys -q -l "$dir/$1.log" -p "read_verilog -sv -I. -I$root/rtl/board -I$root/rtl/common ${sources[*]} $root/rtl/board/$top.sv;
        hierarchy -top $top -chparam LanesOverride $lanes $cut; $2") >/dev/null 2>"$dir/$1.warnings" || {
      echo "synth.sh: $name: yosys failed ($1 run): $(grep -m1 'ERROR' "$dir/$1.warnings" || tail -n 1 "$dir/$1.warnings")" >&2
      return 1
    }
  }
  yosys_on yosys "$synth; $netlist; tee -q -o $dir/stat.json stat -json; $timing; tee -q -o $dir/sta.txt sta" || return 1
  local lut ff dsp bram spram
  read -r lut ff dsp bram spram < <(resources "$family" "$dir/stat.json" design)
  if $blocks; then
    # Every kept module has one instance in the tops, so a module's stat is its block's.
    yosys_on blocks "setattr -mod -set keep_hierarchy 1 *evms_ba_filter *evms_intake *evms_climbs_core *evms_serial_climbs *evms_mean_shift *evms_merge *evms_seeded_climbs \
        *evms_mode_links *evms_warm_seeds *evms_centroid *evms_tracker *evms_mul* *evms_recip *evms_core *evms_board; $synth; tee -q -o $dir/blocks_stat.json stat -json" || return 1
    {
      printf '%-11s %7s %7s %5s %5s %5s\n' block LUT FF DSP BRAM SPRAM
      { grep -oE '^      "[^"]+": \{' "$dir/blocks_stat.json" | grep -v '"design"' | sed -E 's/^ *"(.*)": \{$/\1/'; echo design; } | while read -r m; do
        printf '%-11s %7s %7s %5s %5s %5s\n' "$(echo "$m" | sed -E 's/^.*\\evms_([a-z0-9_]+).*$/\1/; s/^(icebreaker|arty)_top$/top/; s/^design$/total/')" \
          $(resources "$family" "$dir/blocks_stat.json" "$m")
      done
    } > "$dir/blocks.txt"
  fi
  # The longest path: its delay, and its blocks and source lines from start to end.
  local logic_ps logic_ns bound critical
  logic_ps=$({ grep -oE "Latest arrival time in '[^']+' is [0-9]+" "$dir/sta.txt" || true; } | awk '{ print $NF }')
  [ -n "$logic_ps" ] || { echo "synth.sh: $name: $dir/sta.txt: no latest arrival time from Yosys sta" >&2; return 1; }
  logic_ns=$(awk -v p="$logic_ps" 'BEGIN { printf "%.2f", p / 1000 }')
  bound=$(awk -v p="$logic_ps" 'BEGIN { printf "%.1f", 1e6 / p }')
  critical=$(awk '/Latest arrival/ { on = 1 } on { print } /C->Q\)|Arrival histogram/ { on = 0 }' "$dir/sta.txt" | tr -d '\\' |
    grep -oE 'u_board(\.[ug]_[a-z0-9_]+)+|[a-z0-9_]+\.sv:[0-9]+' | sed 's/^u_board\.//' | tac | awk '!seen[$0]++' | paste -sd' ')
  local fits=true
  for r in lut ff dsp bram spram; do
    awk -v u="${!r}" -v c="${capacity[${family}_$r]}" 'BEGIN { exit !(u > c) }' && fits=false
  done
  local fmax=null worst=null bitstream=null
  if [ "$family" = ice40 ] && [ $fits = true ]; then
    local f=() best_seed="" best=0
    for seed in $(seq 1 "$seeds"); do
      if nextpnr-ice40 --up5k --package sg48 --pcf "$root/constraints/icebreaker.pcf" --json "$dir/netlist.json" --freq "$ice40_mhz" \
           --seed "$seed" --report "$dir/pnr_$seed.json" --asc "$dir/top_$seed.asc" -q -l "$dir/pnr_$seed.log" >/dev/null 2>&1; then
        local achieved
        achieved=$(grep -oE '"achieved": [0-9.]+' "$dir/pnr_$seed.json" | head -1 | awk '{ print $2 }')
        f+=("$achieved")
        if awk -v a="$achieved" -v b="$best" 'BEGIN { exit !(a > b) }'; then best=$achieved best_seed=$seed; fi
      fi
    done
    if [ ${#f[@]} -gt 0 ]; then
      fmax=$(printf '%s\n' "${f[@]}" | sort -g | awk '{ v[NR] = $1 } END { printf "%.1f", NR % 2 ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2 }')
      worst=$(printf '%s\n' "${f[@]}" | sort -g | head -1 | awk '{ printf "%.1f", $1 }')
      # A seed that failed to route counts as the worst.
      [ ${#f[@]} -eq "$seeds" ] || worst=0.0
      icepack "$dir/top_$best_seed.asc" "$dir/$top.bin" || { echo "synth.sh: $name: icepack failed" >&2; return 1; }
      bitstream="\"$dir/$top.bin\""
    else
      fits=false
    fi
  fi
  printf '  "%s": {"top": "%s", "lanes": %s, "lut": %s, "ff": %s, "dsp": %s, "bram": %s, "spram": %s, "fits": %s, "fmax_mhz": %s, "fmax_worst_mhz": %s, "bitstream": %s, "logic_ns": %s, "fmax_bound_mhz": %s, "critical": "%s"}' \
    "$name" "$top" "$lanes" "$lut" "$ff" "$dsp" "$bram" "$spram" "$fits" "$fmax" "$worst" "$bitstream" "$logic_ns" "$bound" "$critical" > "$dir/entry.json"
  echo "synth.sh: $name done: $lut LUT, $ff FF, $dsp DSP, $bram BRAM, $spram SPRAM, fits $fits, routed Fmax $fmax MHz (worst $worst), logic path $logic_ns ns (Fmax <= $bound MHz) through $critical" >&2
}

for c in "${configs[@]}"; do
  [[ $c =~ ^(ice40|ice40core|xc7)_p[0-9]+$ ]] || { echo "synth.sh: unknown configuration '$c'" >&2; exit 2; }
  while [ "$(jobs -rp | wc -l)" -ge "$jobs" ]; do wait -n; done
  run_config "$c" &
done
wait
failed=()
for c in "${configs[@]}"; do [ -f "$work/$c/entry.json" ] || failed+=("$c"); done
[ ${#failed[@]} -eq 0 ] || { echo "synth.sh: no result for ${failed[*]} (see the messages above); $out not written" >&2; exit 1; }
{
  echo "{"
  first=true
  for c in "${configs[@]}"; do
    $first || echo ","
    first=false
    cat "$work/$c/entry.json"
  done
  echo
  echo "}"
} > "$out"
echo "synth.sh: wrote $out" >&2
