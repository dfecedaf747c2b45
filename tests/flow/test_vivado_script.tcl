# constraints/flow/vivado_arty.tcl under tclsh, with Vivado's commands recorded instead of run:
# it must read every source synth.sh gives Yosys, in order, with include directories that hold
# every file the sources include and every table they read; run synthesis, placement and
# routing for the Arty's device; and write the bitstream only when the routed slack is not
# negative, failing otherwise.
#
#   tclsh tests/flow/test_vivado_script.tcl REPO_ROOT WORK_DIR
set root [file normalize [lindex $argv 0]]
set work [file normalize [lindex $argv 1]]
set failures 0
# CONDITION is an expression, evaluated where check is called.
proc check {condition message} {
  if {![uplevel 1 [list expr $condition]]} { puts "FAILED: $message"; incr ::failures }
}

set vivado_commands {read_verilog read_xdc read_mem synth_design opt_design place_design phys_opt_design route_design
  report_utilization report_timing_summary write_checkpoint write_bitstream get_timing_paths}
foreach command $vivado_commands {
  proc $command args "lappend ::calls \[list $command {*}\$args\]; return timing_path"
}
proc get_property {name object} { return $::routed_slack }

# Runs the script with the routed design's worst slack SLACK: its calls, and its error or "".
proc run_script {slack out} {
  set ::calls {}
  set ::routed_slack $slack
  set ::argv [list $out]
  set ::argc 1
  set here [pwd]
  set failed [catch {uplevel #0 [list source [file join $::root constraints flow vivado_arty.tcl]]} message]
  cd $here
  return [list $::calls [expr {$failed ? $message : ""}]]
}
proc calls_of {calls command} {
  set found {}
  foreach c $calls { if {[lindex $c 0] eq $command} { lappend found [lrange $c 1 end] } }
  return $found
}
proc option {arguments name} {
  set i [lsearch -exact $arguments $name]
  return [expr {$i < 0 ? "" : [lindex $arguments [expr {$i + 1}]]}]
}
proc file_list {name} {
  set paths {}
  set f [open [file join $::root rtl $name]]
  foreach line [split [read $f] \n] { if {[string trim $line] ne ""} { lappend paths [file join $::root rtl [string trim $line]] } }
  close $f
  return $paths
}

# ---- a routed design that meets the clock ------------------------------------------------------
lassign [run_script 0.412 [file join $work met]] calls error
check {$error eq ""} "the run failed with slack 0.412 ns: $error"

set wanted [concat [file_list core.f] [file_list board.f] [list [file join $root rtl board evms_arty_top.sv]]]
set read {}
foreach c [calls_of $calls read_verilog] {
  check {[lindex $c 0] eq "-sv"} "read_verilog without -sv: $c"
  lappend read [file normalize [lindex $c end]]
}
check {$read eq $wanted} "the sources read differ from rtl/core.f, rtl/board.f and the top:\n  read   $read\n  wanted $wanted"
foreach path $read { check {[file exists $path]} "$path does not exist" }
check {[calls_of $calls read_xdc] eq [list [list [file join $root constraints arty_a7.xdc]]]} "the constraints read: [calls_of $calls read_xdc]"

set synth [calls_of $calls synth_design]
check {[llength $synth] == 1} "synth_design runs [llength $synth] times"
set synth [lindex $synth 0]
check {[option $synth -top] eq "evms_arty_top"} "synth_design's top: [option $synth -top]"
check {[option $synth -part] eq "xc7a35ticsg324-1L"} "synth_design's part: [option $synth -part]"
check {[option $synth -verilog_define] eq "SYNTHESIS"} "synth_design's define: [option $synth -verilog_define]"
set include_dirs [option $synth -include_dirs]
# Every `include of every source (and of the headers they include) is in an include directory.
set pending $read
set seen {}
while {[llength $pending] > 0} {
  set pending [lassign $pending path]
  set f [open $path]
  set text [read $f]
  close $f
  foreach {_ name} [regexp -all -inline {`include\s+"([^"]+)"} $text] {
    if {[dict exists $seen $name]} continue
    set where ""
    foreach dir $include_dirs { if {[file exists [file join $dir $name]]} { set where [file join $dir $name]; break } }
    check {$where ne ""} "$path includes $name, which no include directory holds ($include_dirs)"
    dict set seen $name 1
    if {$where ne ""} { lappend pending $where }
  }
}
check {[dict size $seen] >= 3} "the sources include [dict size $seen] headers"
# Every table the generated headers name is read as a memory file.
set mems {}
foreach c [calls_of $calls read_mem] { lappend mems [file tail [lindex $c 0]] }
foreach header [glob [file join $root rtl generated *.svh]] {
  set f [open $header]
  foreach {_ name} [regexp -all -inline {"[^"]*/([^"/]+\.mem)"} [read $f]] {
    check {[lsearch -exact $mems $name] >= 0} "[file tail $header] names $name, which the script does not read_mem"
  }
  close $f
}
check {[llength $mems] > 0} "no memory file read"

set order {}
foreach c $calls {
  if {[lindex $c 0] in {synth_design opt_design place_design route_design write_bitstream}} { lappend order [lindex $c 0] }
}
check {$order eq {synth_design opt_design place_design route_design write_bitstream}} "the steps ran as $order"
check {[file tail [lindex [lindex [calls_of $calls write_bitstream] 0] end]] eq "evms_arty_top.bit"} "the bitstream's name"
check {[file isdirectory [file join $work met]]} "OUT_DIR is not made"

# ---- a routed design that misses it: no bitstream, and an error ---------------------------------
lassign [run_script -0.113 [file join $work missed]] calls error
check {[string match "*misses the 10 ns clock (worst setup slack -0.113 ns*" $error]} "with slack -0.113 ns the error is: '$error'"
check {[llength [calls_of $calls write_bitstream]] == 0} "a bitstream was written with negative slack"
check {[llength [calls_of $calls route_design]] == 1} "routing did not run"

if {$failures > 0} { exit 1 }
puts "vivado_arty.tcl: [llength $read] sources, [dict size $seen] headers, [llength $mems] tables; bitstream only at non-negative slack"
