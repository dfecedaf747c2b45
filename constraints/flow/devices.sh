# The devices the builds are synthesized for, read by synth.sh (its "fits" verdict) and
# compare.sh (the budget): the iCE40 UP5K (iCEBreaker) and the XC7A35T (Arty A7-35T).
# shellcheck shell=bash
declare -A capacity=([ice40_lut]=5280 [ice40_ff]=5280 [ice40_dsp]=8 [ice40_bram]=30 [ice40_spram]=4
                     [xc7_lut]=20800 [xc7_ff]=41600 [xc7_dsp]=90 [xc7_bram]=50 [xc7_spram]=0)
# The share of an XC7A35T's LUTs an Arty configuration may take: the room Vivado's placer needs to
# route 100 MHz, and what issue 15 asks of the Arty build.
xc7_lut_budget_percent=80
