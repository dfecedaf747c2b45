# The Arty A7-35T's bitstream by Vivado's place and route (non-project mode), from the sources
# synth.sh gives Yosys: rtl/core.f, rtl/board.f, rtl/board/evms_arty_top.sv and
# constraints/arty_a7.xdc. Vivado is not a Debian package, so no test here runs it;
# Constraints.TheVivadoScriptReadsTheArtysSourcesAndFailsOnNegativeSlack (sim/CMakeLists.txt)
# runs this script under tclsh with Vivado's commands recorded instead.
#
#   vivado -mode batch -source constraints/flow/vivado_arty.tcl [-tclargs OUT_DIR]
#
# OUT_DIR (default build/vivado) gets evms_arty_top.bit, utilization.txt, timing.txt and the
# routed checkpoint. The run fails, with Vivado's non-zero exit, when the routed design misses
# the 10 ns clock of arty_a7.xdc.

set root [file normalize [file join [file dirname [info script]] .. ..]]
set out [file normalize [expr {$argc > 0 ? [lindex $argv 0] : [file join $root build vivado]}]]
# The Arty A7-35's device (Digilent's reference manual).
set part xc7a35ticsg324-1L
set top evms_arty_top

# A file list of rtl/: one path a line, relative to rtl/.
proc rtl_list {root name} {
  set f [open [file join $root rtl $name]]
  set paths {}
  foreach line [split [read $f] \n] {
    set line [string trim $line]
    if {$line ne "" && ![string match "#*" $line]} { lappend paths [file join $root rtl $line] }
  }
  close $f
  return $paths
}

file mkdir $out
foreach source [concat [rtl_list $root core.f] [rtl_list $root board.f] [list [file join $root rtl board $top.sv]]] {
  read_verilog -sv $source
}
read_xdc [file join $root constraints arty_a7.xdc]
# The exp and reciprocal tables the RTL reads with $readmemh, by names relative to rtl/generated.
foreach table [lsort [glob [file join $root rtl generated *.mem]]] { read_mem $table }
cd [file join $root rtl generated]

synth_design -top $top -part $part -verilog_define SYNTHESIS \
  -include_dirs [list [file join $root rtl generated] [file join $root rtl board] [file join $root rtl common]]
opt_design
place_design
phys_opt_design
route_design
report_utilization -file [file join $out utilization.txt]
report_timing_summary -file [file join $out timing.txt]
write_checkpoint -force [file join $out $top.routed.dcp]

set slack [get_property SLACK [get_timing_paths -delay_type max -max_paths 1]]
if {$slack eq "" || $slack < 0} {
  error "vivado_arty.tcl: the routed design misses the 10 ns clock (worst setup slack ${slack} ns, $out/timing.txt)"
}
write_bitstream -force [file join $out $top.bit]
puts "vivado_arty.tcl: $out/$top.bit, worst setup slack $slack ns at 100 MHz"
