#!/bin/sh
# Runs the libFuzzer targets of tests/fuzz: `tests/fuzz/run.sh [SECONDS] [TARGET...]` (default
# 20 s each, every target). Builds them in build-fuzz with clang when needed. Seed corpora are
# cut from ../shared/data/real at run time when it is there (never committed); the dictionaries
# hold each format's magic words. Limits: 5 s an input, 1 GiB an allocation. Prints the runs
# and coverage per target; what a target finds is kept in build-fuzz/finds/TARGET and makes the
# script fail. The targets run as many at a time as there are cores (each fuzzer is one
# process on one core). For hours by hand: tests/fuzz/run.sh 3600.
set -eu
cd "$(dirname "$0")/../.."
seconds=${1:-20}
[ $# -gt 0 ] && shift
targets=${*:-"aedat2 aedat3 aedat4 evt2 evt21 evt3 dat csv text ros1 ros2 mcap npy streams config scoring"}
command -v clang++ >/dev/null || { echo "fuzz: clang++ is not installed (apt install clang)"; exit 1; }
if [ ! -f build-fuzz/CMakeCache.txt ]; then
  cmake -S . -B build-fuzz -DCMAKE_CXX_COMPILER=clang++ -DEVMS_FUZZ=ON -DCMAKE_BUILD_TYPE=RelWithDebInfo >/dev/null
fi
cmake --build build-fuzz -j2 --target fuzz_all >/dev/null
real=../shared/data/real
# The bytes of a shared recording after its first N bytes (the header the harness writes), or nothing.
cut_from() {  # file skip count out
  [ -f "$real/$1" ] && tail -c +"$(($2 + 1))" "$real/$1" | head -c "$3" >"$4" || true
}
# The offset just past a Prophesee header's "% end" line.
after_end() { grep -abo '% end' "$real/$1" 2>/dev/null | head -1 | cut -d: -f1 | awk '{print $1 + 6}'; }
# Corpus and dictionary of target $1, then its run for $seconds; its verdict line goes to
# build-fuzz/fuzz_$1.verdict and a find makes it fail.
fuzz_one() {
  t=$1 corpus=build-fuzz/corpus/$1 finds=build-fuzz/finds/$1
  mkdir -p "$corpus" "$finds"
  case $t in
    aedat4) cut_from dvxplorer_indoor.aedat4 14 65536 "$corpus/shared" ;;
    evt2) [ -f "$real/gen3_moving_blob.evt2.raw" ] && cut_from gen3_moving_blob.evt2.raw "$(after_end gen3_moving_blob.evt2.raw)" 8192 "$corpus/shared" ;;
    evt3) [ -f "$real/gen41_dense_scene.evt3.raw" ] && cut_from gen41_dense_scene.evt3.raw "$(after_end gen41_dense_scene.evt3.raw)" 8192 "$corpus/shared" ;;
    dat) printf '\000\010' >"$corpus/seed" ;;
    ros2) cut_from ros2/libcaer_rollover/libcaer_rollover_0.db3 16 65536 "$corpus/shared" ;;
    csv) printf 't_us,x,y,p\n10,1,2,1\n20,3,4,0\n' >"$corpus/seed"
      printf '%%geometry:64,48\n1,2,1,10\n3,4,0,20\n' >"$corpus/metavision"
      printf '"Polarity", Timestamp ,label,Y,X\n1,10,-1,2,1\n0,20,7,4,3\n' >"$corpus/named"
      printf 't_s,x,y,pol\n0.000010,1,2,1\n' >"$corpus/seconds" ;;
    ros1) printf '\051\000\000\000\004\000\000\000\157\160\075\005\020\000\000\000\143\157\155\160\162\145\163\163\151\157\156\075\156\157\156\145\011\000\000\000\163\151\172\145\075\265\000\000\000\265\000\000\000\041\000\000\000\004\000\000\000\157\160\075\007\011\000\000\000\143\157\156\156\075\000\000\000\000\010\000\000\000\164\157\160\151\143\075\057\145\050\000\000\000\010\000\000\000\164\157\160\151\143\075\057\145\030\000\000\000\164\171\160\145\075\144\166\163\137\155\163\147\163\057\105\166\145\156\164\101\162\162\141\171\046\000\000\000\004\000\000\000\157\160\075\002\011\000\000\000\143\157\156\156\075\000\000\000\000\015\000\000\000\164\151\155\145\075\000\000\000\000\000\000\000\000\066\000\000\000\001\000\000\000\144\000\000\000\000\000\000\000\000\000\000\000\264\000\000\000\360\000\000\000\002\000\000\000\001\000\002\000\144\000\000\000\350\003\000\000\001\003\000\004\000\144\000\000\000\320\007\000\000\000' >"$corpus/seed" ;;  # a chunk: a dvs_msgs/EventArray connection and a message of 2 events
    mcap) printf '\001\014\000\000\000\000\000\000\000\004\000\000\000\162\157\163\062\000\000\000\000\003\054\000\000\000\000\000\000\000\001\000\027\000\000\000\144\166\163\137\155\163\147\163\057\155\163\147\057\105\166\145\156\164\101\162\162\141\171\007\000\000\000\162\157\163\062\155\163\147\000\000\000\000\004\025\000\000\000\000\000\000\000\001\000\001\000\002\000\000\000\057\145\003\000\000\000\143\144\162\000\000\000\000\005\103\000\000\000\000\000\000\000\001\000\000\000\000\000\001\000\000\000\000\000\000\000\001\000\000\000\000\000\000\000\000\001\000\000\001\000\000\000\000\000\000\000\001\000\000\000\000\000\000\000\264\000\000\000\360\000\000\000\001\000\000\000\003\000\004\000\001\000\000\000\210\023\000\000\001\017\004\000\000\000\000\000\000\000\000\000\000\000' >"$corpus/seed" ;;  # header, schema, channel, a dvs_msgs/EventArray message of 1 event, data end
    npy) printf "\166\000{'descr': [('t', '<i8'), ('x', '<u2'), ('y', '<u2'), ('p', '|b1')], 'fortran_order': False, 'shape': (2,), }%9s\n" "" >"$corpus/seed"
      printf '\012\000\000\000\000\000\000\000\001\000\002\000\001\024\000\000\000\000\000\000\000\003\000\004\000\000' >>"$corpus/seed" ;;
    text) printf '0.000010 1 2 1\n0.000020 3 4 0\n' >"$corpus/seed" ;;
    scoring) printf '10,1,2,1,3\n20,3,4,0,-1\n10050,3,confirmed,21.5,50,-3e2,0,100\n' >"$corpus/seed" ;;
    config) [ -x build/bin/evms ] && build/bin/evms params --config >"$corpus/defaults" || printf 'preset: paper\nbandwidth: 0.2\n' >"$corpus/seed" ;;
  esac
  dict=""
  [ -f "tests/fuzz/dict/$t.dict" ] && dict="-dict=tests/fuzz/dict/$t.dict"
  log=build-fuzz/fuzz_$t.log verdict=build-fuzz/fuzz_$t.verdict
  if build-fuzz/bin/fuzz_$t "$corpus" $dict -max_total_time="$seconds" -timeout=5 -malloc_limit_mb=1024 -rss_limit_mb=2048 \
      -artifact_prefix="$finds/" -print_final_stats=1 >"$log" 2>&1; then
    echo "fuzz_$t: $(grep -o 'stat::number_of_executed_units: *[0-9]*' "$log" | grep -o '[0-9]*$') runs in ${seconds} s, $(grep -o 'cov: [0-9]*' "$log" | tail -1), no finds" >"$verdict"
  else
    { echo "fuzz_$t: FOUND A BUG (input kept in $finds; log $log):"; grep -E 'ERROR|SUMMARY|Test unit written' "$log" | head -5; } >"$verdict"
    return 1
  fi
}
# Batches of one target per core; each batch waits for its slowest (they all run $seconds).
cores=$(nproc 2>/dev/null || echo 1)
failed=0
set -- $targets
while [ $# -gt 0 ]; do
  batch="" pids="" running=0
  while [ $# -gt 0 ] && [ "$running" -lt "$cores" ]; do
    fuzz_one "$1" &
    batch="$batch $1" pids="$pids $!" running=$((running + 1))
    shift
  done
  for p in $pids; do wait "$p" || failed=1; done
  for t in $batch; do cat "build-fuzz/fuzz_$t.verdict"; done
done
exit $failed
