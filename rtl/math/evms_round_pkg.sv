// Rounding half up by a right shift, as hls/math's Reciprocal::divide rounds its quotients:
// round(p * 2^-s) = (p + 2^(s-1)) >> s for s >= 1. The same value is ((p >> (s - 1)) + 1) >> 1,
// whose add only needs the bits the caller keeps (Yosys trims the rest), not all 64, and whose
// shifter takes s - 1 straight from a register. p is non-negative.
//
// shr_rnd is the C++ core's shr_rnd (hls/math): a signed value rounded half up by a right shift
// of s bits, or shifted left when s <= 0; it serves a shift fixed by the parameters.
package evms_round_pkg;
  function automatic [63:0] round_shift(input [63:0] p, input [6:0] s_minus_1);
    begin
      round_shift = ((p >> s_minus_1) + 64'd1) >> 1;
    end
  endfunction
  function automatic signed [63:0] shr_rnd(input signed [63:0] v, input integer s);
    begin
      if (s <= 0) shr_rnd = v <<< (-s);
      else shr_rnd = (v + (64'sd1 <<< (s - 1))) >>> s;
    end
  endfunction
endpackage
