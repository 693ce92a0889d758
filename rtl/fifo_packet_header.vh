// Byte i (0..6) of a packet's header in the output FIFO's format (the one
// rtl/link_framer.v frames, docs/protocol.md): type, t u32 LE, len u16 LE.
// One definition for every block that writes packets into the FIFO itself
// (rtl/list_packet_writer.v, rtl/taxel_packetizer.v's dense packet); a
// module includes it inside its body.
function automatic [7:0] fifo_header_byte(input [2:0] i, input [7:0] ptype, input [31:0] pt,
                                          input [15:0] plen);
  case (i)
    3'd0: fifo_header_byte = ptype;
    3'd1: fifo_header_byte = pt[7:0];
    3'd2: fifo_header_byte = pt[15:8];
    3'd3: fifo_header_byte = pt[23:16];
    3'd4: fifo_header_byte = pt[31:24];
    3'd5: fifo_header_byte = plen[7:0];
    default: fifo_header_byte = plen[15:8];
  endcase
endfunction
