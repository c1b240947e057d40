// encoder_stub: a simple behavioural EnDat 2.2 encoder for tb_stub (not synthesizable).
// It answers "Encoder send position values" (2.1), "... with additional data" (2.2, none
// selected), "Selection of memory area" and "Encoder send parameters"; word 13 of MRS A1h holds
// the position width as D297403 3.5.6 stores it (8000h | bits). It checks no timing: a stub as
// a designer would write one, to be compared with endatsim's encoder.
// Its ports are the encoder's pins; the testbench puts the cable between them and the master.
`timescale 1ns / 1ps
`default_nettype none

module encoder_stub #(
    parameter integer POS_BITS = 25,
    parameter real T_CAL_NS = 5000.0,  // FE1 -> start bit (D297403 2.3.2 t_cal)
    parameter real T_AC_NS = 50000.0,  // last payload bit -> start bit of a parameter answer
    parameter real T_M_NS = 10000.0,  // CLOCK HIGH this long ends a frame (t_m)
    parameter real T_OUT_NS = 20.0,  // CLOCK edge in -> DATA out (logic and transceivers)
    parameter [63:0] POS_START = 64'h0000_0000_0123_4567,
    parameter [63:0] POS_STEP = 64'h0000_0000_0010_2031  // changes many bits from frame to frame
) (
    input  wire        clock,
    input  wire        data_in,
    output reg         data_out,
    output reg         data_oe,
    output reg  [63:0] last_position_22,  // the position of the latest 2.2 position frame
    output integer     frames_21,
    output integer     frames_22,
    output integer     frames_param
);

  localparam [63:0] MASK = (POS_BITS >= 64) ? ~64'd0 : ((64'd1 << POS_BITS) - 64'd1);
  localparam integer S_IDLE = 0, S_HEAD = 1, S_WAIT = 2, S_SEND = 3, S_END = 4, S_NONE = 5;

  integer state, fe, re, turn, first_re, width, idx, n, k;
  realtime t_fe1, t_last_re, t_ready, t_hi_max;
  reg [5:0] mode;
  reg [23:0] payload;
  reg payload_cmd;
  reg [0:127] ans;  // bit 0 goes first on the wire
  reg [63:0] pos, latched;
  reg [7:0] mrs;
  reg [15:0] value;
  reg [4:0] crc;
  reg dout, doe;  // DATA and its driver enable before the output delay

  // Transport delays: each edge comes out, however short the bit.
  always @(dout) data_out <= #(T_OUT_NS) dout;
  always @(doe) data_oe <= #(T_OUT_NS) doe;

  function [4:0] crc_step(input [4:0] c, input b);  // D297403 A4: x^5 + x^3 + x + 1
    crc_step = {c[3:0], 1'b0} ^ ((b ^ c[4]) ? 5'h0B : 5'h00);
  endfunction

  // Appends the CRC over bits 1 .. n (everything after the start bit) at n + 1 .. n + 5.
  task add_crc(input integer nbits);
    begin
      crc = 5'h1F;  // A4.4.1: preset to 1
      for (k = 1; k <= nbits; k = k + 1) crc = crc_step(crc, ans[k]);
      crc = ~crc;  // sent inverted, MSB first
      for (k = 0; k < 5; k = k + 1) ans[nbits+1+k] = crc[4-k];
      width = nbits + 6;
    end
  endtask

  task position_answer(input v22);
    begin
      ans = 128'd0;
      ans[0] = 1'b1;  // S
      ans[1] = 1'b0;  // F1: no error
      n = 2;
      if (v22) begin
        ans[2] = 1'b1;  // F2 is low-active
        n = 3;
      end
      for (k = 0; k < POS_BITS; k = k + 1) ans[n+k] = latched[k];  // LSB first
      add_crc(n + POS_BITS - 1);
    end
  endtask

  task parameter_answer(input [7:0] addr, input [15:0] par);
    begin
      ans = 128'd0;
      ans[0] = 1'b1;
      for (k = 0; k < 8; k = k + 1) ans[1+k] = addr[7-k];
      for (k = 0; k < 16; k = k + 1) ans[9+k] = par[15-k];
      add_crc(24);
    end
  endtask

  initial begin
    dout = 1'b0;
    doe = 1'b1;  // idle: DATA driven LOW
    data_out = 1'b0;
    data_oe = 1'b1;
    state = S_IDLE;
    fe = 0;
    re = 0;
    turn = 9;
    t_last_re = 0.0;
    t_hi_max = 0.0;
    pos = POS_START & MASK;
    latched = 64'd0;
    last_position_22 = 64'd0;
    mrs = 8'h00;
    frames_21 = 0;
    frames_22 = 0;
    frames_param = 0;
  end

  // A new frame: after idle, after CLOCK HIGH for t_m, or after the answer when CLOCK stayed HIGH
  // longer than twice the frame's longest HIGH phase (more pulses at the frame's own rate are
  // extra clocks, not a new frame).
  always @(negedge clock) begin
    if (state == S_IDLE || ($realtime - t_last_re) >= T_M_NS ||
        (state == S_END && ($realtime - t_last_re) > 2.0 * t_hi_max)) begin
      // FE1: latch the position, release DATA
      state = S_HEAD;
      fe = 1;
      re = 0;
      turn = 9;
      mode = 6'd0;
      payload = 24'd0;
      payload_cmd = 1'b0;
      t_fe1 = $realtime;
      t_hi_max = 0.0;
      latched = pos;
      doe = 1'b0;
    end else begin
      fe = fe + 1;
      if ($realtime - t_last_re > t_hi_max) t_hi_max = $realtime - t_last_re;
      if (fe == turn) begin  // take DATA back, LOW until the start bit
        doe = 1'b1;
        dout = 1'b0;
      end
    end
  end

  always @(posedge clock) begin
    t_last_re = $realtime;
    re = re + 1;
    case (state)
      S_HEAD: begin
        if (re >= 3 && re <= 8) mode = {mode[4:0], data_in};
        else if (payload_cmd && re >= 9 && re <= 32) payload = {payload[22:0], data_in};
        if (re == 8) begin
          case (mode)
            6'b000111, 6'b111000: begin
              position_answer(mode == 6'b111000);
              if (mode == 6'b111000) begin
                last_position_22 = latched;
                frames_22 = frames_22 + 1;
              end else frames_21 = frames_21 + 1;
              pos = (pos + POS_STEP) & MASK;
              state = S_WAIT;
              first_re = 11;
              t_ready = t_fe1 + T_CAL_NS;
            end
            6'b001110, 6'b100011: begin
              payload_cmd = 1'b1;
              turn = 33;
            end
            default: state = S_NONE;  // not supported: no start bit
          endcase
        end
        if (payload_cmd && re == 32) begin
          if (mode == 6'b001110) begin
            mrs = payload[23:16];
            parameter_answer(payload[23:16], payload[15:0]);
          end else begin
            value = (mrs == 8'hA1 && payload[23:16] == 8'h0D) ? (16'h8000 | POS_BITS[15:0]) : 16'h0000;
            parameter_answer(payload[23:16], value);
          end
          frames_param = frames_param + 1;
          state = S_WAIT;
          first_re = 35;
          t_ready = $realtime + T_AC_NS;
        end
      end
      S_WAIT: begin
        if (re >= first_re && $realtime >= t_ready) begin
          dout = 1'b1;  // start bit
          idx = 1;
          state = S_SEND;
        end
      end
      S_SEND: begin
        if (idx < width) begin
          dout = ans[idx];
          idx = idx + 1;
        end else begin
          dout = 1'b1;  // end of data: HIGH
          state = S_END;
        end
      end
      default: ;
    endcase
  end

endmodule

`default_nettype wire
