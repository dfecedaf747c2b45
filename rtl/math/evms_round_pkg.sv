// Rounding half up by a right shift, as hls/math's Reciprocal::divide rounds its quotients:
// round(p * 2^-s) = (p + 2^(s-1)) >> s for s >= 1. The same value is ((p >> (s - 1)) + 1) >> 1,
// whose add only needs the bits the caller keeps (Yosys trims the rest), not all 64, and whose
// shifter takes s - 1 straight from a register. p is non-negative.
package evms_round_pkg;
  function automatic [63:0] round_shift(input [63:0] p, input [6:0] s_minus_1);
    begin
      round_shift = ((p >> s_minus_1) + 64'd1) >> 1;
    end
  endfunction
endpackage
