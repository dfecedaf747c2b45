// CRC-16/CCITT-FALSE (polynomial 0x1021, initial 0xFFFF, no reflection, no final XOR), one
// byte at a time: the link's frame check (docs/link.md).
package evms_crc16_pkg;
  function automatic [15:0] crc16_byte(input [15:0] crc, input [7:0] b);
    integer k;
    reg [15:0] c;
    begin
      c = crc ^ {b, 8'h00};
      for (k = 0; k < 8; k = k + 1) c = c[15] ? (c << 1) ^ 16'h1021 : (c << 1);
      crc16_byte = c;
    end
  endfunction
endpackage
