// endat_master: a small synthesizable EnDat 2.2 master (HEIDENHAIN D297403), the example
// that examples/hdl/run_stub.sh and the endatsim VPI bridge exercise.
//
// After reset it
//   1. measures the propagation delay t_D with N_MEAS "Encoder send position values" frames
//      (000111) at MEAS_HZ (D297403 2.1.2),
//   2. reads N_POS positions with "Encoder send position values with additional data"
//      (111000, no additional data selected) at F_C_HZ, sampling each bit t_D after the edge
//      that launched it (D297403 2.3),
//   3. reads word 13 of the encoder manufacturer's parameters (MRS A1h, address 0Dh) with the
//      EnDat 2.1 commands "Selection of memory area" and "Encoder send parameters",
//   4. raises done and leaves CLOCK HIGH.
//
// Frame positions follow the spec's figures: FEk / REk is the k-th falling / rising CLOCK edge of
// a frame, FE1 opens it. The master drives DATA from FE2 (a 0), sends the mode bits on FE3..FE8
// (and a 2.1 payload of 8 + 16 bits on FE9..FE32), and releases DATA on FE9 (FE33).
// The encoder's bit after REk is "slot k".
//
// DEFECT (each breaks one rule of D297403 2.3.2 on purpose, everything else stays right):
//   1: t_ST 1 us instead of 2 us at 8 MHz (note 8)
//   2: only ~2 us of CLOCK HIGH between position reads (t_m + t_R, notes 3, 9)
//   3: no delay measurement, position reads at 2 MHz sampled at the falling edge (f_c against
//      the cable without compensation, 2.1.1 / 2.1.2)
//
// SYS_HZ must be at least 8 x F_C_HZ: sys_clk is the t_D counter, and D297403 2.1.2 wants it at
// eight times the compensated f_c or more (80 MHz for 8 MHz: 12.5 ns counts, T/8 = 15.6 ns).
`timescale 1ns / 1ps
`default_nettype none

module endat_master #(
    parameter integer SYS_HZ   = 80_000_000,
    parameter integer F_C_HZ   = 8_000_000,
    parameter integer MEAS_HZ  = 200_000,
    parameter integer POS_BITS = 25,
    parameter integer N_MEAS   = 3,
    parameter integer N_POS    = 8,
    parameter integer CYCLE_US = 62,
    parameter integer DEFECT   = 0
) (
    input  wire        sys_clk,
    input  wire        rst,
    input  wire        data_in,
    output reg         endat_clock = 1'b1,  // power-up values as after reset: CLOCK HIGH,
    output reg         data_out = 1'b0,     // DATA not driven
    output reg         data_oe = 1'b0,
    output reg  [63:0] position,
    output reg         position_valid,
    output reg         crc_error,
    output reg  [15:0] param_value,
    output reg         param_valid,
    output reg         done
);

  // ---- timing, in sys_clk cycles -------------------------------------------------------------
  // Periods round up, so a clock is never faster than asked; minimum times round up too.
  localparam integer CYC_US = (SYS_HZ + 999_999) / 1_000_000;
  localparam integer F_POS = (DEFECT == 3) ? 2_000_000 : F_C_HZ;
  localparam integer P_POS = (SYS_HZ + F_POS - 1) / F_POS;
  localparam integer P_MEAS = (SYS_HZ + MEAS_HZ - 1) / MEAS_HZ;
  // D297403 2.3.2 note 8: t_ST 2 us for f_c 2 .. 8 MHz (the first LOW phase, FE1 -> RE1).
  localparam integer T_ST = ((DEFECT == 1) ? 1 : 2) * CYC_US;
  // D297403 2.3.2: t_m max 30 us + t_R 0.5 us, + 0.5 us so rounding never lands on the limit.
  // The same wait covers A2 (after an error handling wait the maximum t_m) and the start.
  localparam integer T_REC = 31 * CYC_US;
  localparam integer T_SHORT = 2 * CYC_US;  // DEFECT 2 only
  // D297403 2.3.2 t_b > 1 ms before a 2.1 parameter frame.
  localparam integer T_B = 1100 * CYC_US;
  localparam integer T_CYCLE = CYCLE_US * CYC_US;
  // Polling limits (2.3.2: polling must not depend on t_cal): t_cal max 1 ms from FE1, t_ac max
  // 12 ms from the last payload bit; each with margin.
  localparam integer T_CAL_GIVEUP = 1100 * CYC_US;
  localparam integer T_AC_GIVEUP = 13_000 * CYC_US;
  localparam integer W_POS21 = POS_BITS + 7;  // S F1 position CRC
  localparam integer W_POS22 = POS_BITS + 8;  // S F1 F2 position CRC
  localparam integer W_PAR = 30;  // S address(8) parameter(16) CRC
  localparam integer MEAS_ROUNDS = 3;  // rounds before giving up on a delay that will not settle
  localparam integer MI_W = (N_MEAS > 1) ? $clog2(N_MEAS) : 1;  // index width of the measurements

  localparam [1:0] K_MEAS = 2'd0, K_POS = 2'd1, K_SEL = 2'd2, K_PAR = 2'd3;
  localparam [2:0] ST_WAIT = 3'd0, ST_FRAME = 3'd1, ST_EVAL = 3'd2, ST_CALC = 3'd3, ST_DONE = 3'd4;

  // ---- DATA input synchronizer ---------------------------------------------------------------
  // Its latency is inside every t_D count and inside every sampling instant alike, so it cancels.
  reg din_s1, din_s2, din_prev;
  always @(posedge sys_clk) begin
    if (rst) begin
      din_s1 <= 1'b0;
      din_s2 <= 1'b0;
      din_prev <= 1'b0;
    end else begin
      din_s1 <= data_in;
      din_s2 <= din_s1;
      din_prev <= din_s2;
    end
  end

  // ---- state ---------------------------------------------------------------------------------
  reg [2:0] st;
  reg [1:0] kind;
  reg [7:0] meas_n, meas_round;
  reg [15:0] pos_n;
  reg round_bad;
  reg [15:0] meas_arr[0:N_MEAS-1];
  reg [15:0] t_d;  // measured t_D in cycles (synchronizer included)
  reg t_d_valid;
  reg [31:0] gap, since_re, since_fe1;
  reg use_cycle;

  // Frame engine.
  reg clk_run, abort;
  reg [15:0] edge_cnt, fe_n, re_n, last_re;
  reg [29:0] tx_sr;  // mode bits, then the 2.1 payload, MSB first
  reg samp_on;
  reg [15:0] samp_cnt, samp_slot;
  reg rx_data, rx_done, rx_fail, seen_low;
  reg [3:0] hi_cnt;
  reg [7:0] rx_idx;
  reg [31:0] poll_cnt;
  reg [4:0] crc_calc, crc_rx;
  reg [63:0] lsb_sr;  // position bits arrive LSB first
  reg [23:0] msb_sr;  // address and parameter arrive MSB first
  reg [15:0] tdc, meas_val;  // D297403 2.1.2 counter: restarted at each RE, saved at the start bit
  reg meas_low, meas_cap;

  // ---- per-frame settings from the frame kind --------------------------------------------------
  reg [15:0] f_p, f_hi, f_lo, f_lo1, f_ds, f_rel;
  reg [5:0] f_mode;
  reg [23:0] f_payload;
  reg [7:0] f_w;
  reg f_comp;
  always @* begin
    f_payload = 24'h000000;
    case (kind)
      K_MEAS: begin
        f_p = P_MEAS[15:0];
        f_mode = 6'b000111;
        f_w = W_POS21[7:0];
      end
      K_POS: begin
        f_p = P_POS[15:0];
        f_mode = 6'b111000;
        f_w = W_POS22[7:0];
      end
      K_SEL: begin
        f_p = P_MEAS[15:0];
        f_mode = 6'b001110;
        f_payload = 24'hA1_0000;  // MRS code A1h: encoder manufacturer's parameters, words 0..15
        f_w = W_PAR[7:0];
      end
      default: begin
        f_p = P_MEAS[15:0];
        f_mode = 6'b100011;
        f_payload = 24'h0D_0000;  // address 0Dh: word 13, clock pulses for the position value
        f_w = W_PAR[7:0];
      end
    endcase
    f_hi = f_p >> 1;
    f_lo = f_p - f_hi;
    f_lo1 = (f_lo > T_ST[15:0]) ? f_lo : T_ST[15:0];
    // Measurement frames are never compensated; afterwards every frame is (t_D known).
    f_comp = (kind != K_MEAS) && t_d_valid;
    // Sample slot k at REk + f_ds: the falling edge (f_hi) without compensation; with it half a
    // period after the bit's edge shows at the synchronizer output (t_d + 1, as tdc counted it).
    f_ds = f_comp ? f_hi + t_d + 16'd1 : f_hi;
    f_rel = (kind == K_SEL || kind == K_PAR) ? 16'd33 : 16'd9;
  end

  // ---- delay measurements agree within T/8 of the compensated period (D297403 2.1.2) -----------
  reg [31:0] msum;
  reg spread_ok;
  reg [31:0] dev;
  integer i;
  always @* begin
    msum = 32'd0;
    for (i = 0; i < N_MEAS; i = i + 1) msum = msum + {16'd0, meas_arr[i]};
    spread_ok = 1'b1;
    for (i = 0; i < N_MEAS; i = i + 1) begin
      dev = N_MEAS * {16'd0, meas_arr[i]};
      dev = (dev > msum) ? dev - msum : msum - dev;
      if ((dev << 3) > N_MEAS * P_POS) spread_ok = 1'b0;
    end
  end
  wire [31:0] mean = (msum + N_MEAS / 2) / N_MEAS;  // rounded
  wire unused_mean_msbs = |mean[31:16];  // t_D in cycles fits 16 bits

  wire crc_ok = !rx_fail && (crc_rx == ~crc_calc);
  wire [4:0] crc_fb = (din_s2 ^ crc_calc[4]) ? 5'h0B : 5'h00;  // A4: x^5 + x^3 + x + 1
  wire [7:0] rx_next = rx_idx + 8'd1;
  wire wait_over = since_re >= gap && (!use_cycle || since_fe1 >= T_CYCLE);
  wire [1:0] first_kind = (DEFECT == 3) ? K_POS : K_MEAS;

  always @(posedge sys_clk) begin
    if (rst) begin
      st <= ST_WAIT;
      kind <= first_kind;
      meas_n <= 8'd0;
      meas_round <= 8'd0;
      pos_n <= 16'd0;
      round_bad <= 1'b0;
      for (i = 0; i < N_MEAS; i = i + 1) meas_arr[i] <= 16'd0;
      t_d <= 16'd0;
      t_d_valid <= 1'b0;
      gap <= T_REC;  // CLOCK HIGH before the first frame: the encoder ends any frame it was in
      since_re <= 32'd0;
      since_fe1 <= 32'd0;
      use_cycle <= 1'b0;
      clk_run <= 1'b0;
      abort <= 1'b0;
      edge_cnt <= 16'd0;
      fe_n <= 16'd0;
      re_n <= 16'd0;
      last_re <= 16'd0;
      tx_sr <= 30'd0;
      samp_on <= 1'b0;
      samp_cnt <= 16'd0;
      samp_slot <= 16'd0;
      rx_data <= 1'b0;
      rx_done <= 1'b0;
      rx_fail <= 1'b0;
      seen_low <= 1'b0;
      hi_cnt <= 4'd0;
      rx_idx <= 8'd0;
      poll_cnt <= 32'd0;
      crc_calc <= 5'h1F;
      crc_rx <= 5'h00;
      lsb_sr <= 64'd0;
      msb_sr <= 24'd0;
      tdc <= 16'd0;
      meas_val <= 16'd0;
      meas_low <= 1'b0;
      meas_cap <= 1'b0;
      endat_clock <= 1'b1;
      data_out <= 1'b0;
      data_oe <= 1'b0;
      position <= 64'd0;
      position_valid <= 1'b0;
      crc_error <= 1'b0;
      param_value <= 16'd0;
      param_valid <= 1'b0;
      done <= 1'b0;
    end else begin
      position_valid <= 1'b0;
      crc_error <= 1'b0;
      param_valid <= 1'b0;
      if (since_re != 32'hFFFF_FFFF) since_re <= since_re + 32'd1;
      if (since_fe1 != 32'hFFFF_FFFF) since_fe1 <= since_fe1 + 32'd1;
      if (tdc != 16'hFFFF) tdc <= tdc + 16'd1;

      case (st)
        // -- CLOCK HIGH until the recovery (or t_b, or the cycle) is over, then FE1 --
        ST_WAIT: begin
          if (wait_over) begin
            st <= ST_FRAME;
            endat_clock <= 1'b0;  // FE1: the encoder latches its position, releases DATA
            clk_run <= 1'b1;
            abort <= 1'b0;
            edge_cnt <= f_lo1 - 16'd1;  // t_ST
            fe_n <= 16'd1;
            re_n <= 16'd0;
            last_re <= 16'd0;
            samp_on <= 1'b0;
            rx_data <= 1'b0;
            rx_done <= 1'b0;
            rx_fail <= 1'b0;
            seen_low <= 1'b0;
            hi_cnt <= 4'd0;
            rx_idx <= 8'd0;
            poll_cnt <= 32'd0;
            crc_calc <= 5'h1F;  // A4.4.1: flip-flops preset to 1
            crc_rx <= 5'h00;
            meas_low <= 1'b0;
            meas_cap <= 1'b0;
            since_fe1 <= 32'd0;
          end
        end

        ST_FRAME: begin
          // -- polling gives up only after t_cal max / t_ac max (D297403 2.3.2);
          // first, so that the restart at the release below takes precedence --
          if (!rx_data && !rx_done) begin
            poll_cnt <= poll_cnt + 32'd1;
            if (poll_cnt >= ((kind == K_SEL || kind == K_PAR) ? T_AC_GIVEUP : T_CAL_GIVEUP)) begin
              rx_done <= 1'b1;
              rx_fail <= 1'b1;
              abort <= 1'b1;
            end
          end

          // -- clock generator --
          if (clk_run) begin
            if (edge_cnt != 16'd0) begin
              edge_cnt <= edge_cnt - 16'd1;
            end else if (endat_clock) begin
              if (abort || (last_re != 16'd0 && re_n >= last_re)) begin
                // The last pulse's RE has brought the end marker: CLOCK stays HIGH.
                clk_run <= 1'b0;
              end else begin
                endat_clock <= 1'b0;
                fe_n <= fe_n + 16'd1;
                edge_cnt <= f_lo - 16'd1;
                if (fe_n + 16'd1 == 16'd2) begin
                  // FE2: the master takes DATA and sends the leading 0 (D297403 2.3)
                  data_oe <= 1'b1;
                  data_out <= 1'b0;
                  tx_sr <= {f_mode, f_payload};
                end else if (fe_n + 16'd1 < f_rel) begin
                  data_out <= tx_sr[29];
                  tx_sr <= {tx_sr[28:0], 1'b0};
                end else if (fe_n + 16'd1 == f_rel) begin
                  // FE9 (FE33 after a payload): hand DATA to the encoder
                  data_oe <= 1'b0;
                  data_out <= 1'b0;
                  poll_cnt <= 32'd0;  // t_ac runs from the last payload bit
                end
              end
            end else begin
              endat_clock <= 1'b1;
              re_n <= re_n + 16'd1;
              edge_cnt <= f_hi - 16'd1;
              since_re <= 32'd0;
              tdc <= 16'd0;
              if (re_n == 16'd0) begin
                samp_on <= 1'b1;
                samp_cnt <= f_ds - 16'd1;
                samp_slot <= 16'd1;
              end
            end
          end

          // -- sampler: slot k at REk + f_ds; it runs on after the last edge for late bits --
          if (samp_on) begin
            if (samp_cnt != 16'd0) begin
              samp_cnt <= samp_cnt - 16'd1;
            end else begin
              samp_cnt <= f_p - 16'd1;
              samp_slot <= samp_slot + 16'd1;
              if (samp_slot >= f_rel && !rx_done) begin
                if (!rx_data) begin
                  // Polling: the line floats HIGH (fail-safe) until the encoder drives it LOW,
                  // so the start bit is the first HIGH after a LOW (docs/model.md §1).
                  if (!seen_low) begin
                    if (!din_s2) seen_low <= 1'b1;
                    else if (hi_cnt == 4'd7) begin
                      // Eight HIGH slots and never LOW: type I error handling (D297403 A2)
                      rx_done <= 1'b1;
                      rx_fail <= 1'b1;
                      abort <= 1'b1;
                    end else hi_cnt <= hi_cnt + 4'd1;
                  end else if (din_s2) begin
                    rx_data <= 1'b1;
                    rx_idx <= 8'd1;
                    // One more pulse after the last bit (docs/model.md §5)
                    last_re <= samp_slot + {8'd0, f_w};
                  end
                end else begin
                  rx_idx <= rx_next;
                  if (rx_next <= f_w - 8'd5) begin
                    crc_calc <= {crc_calc[3:0], 1'b0} ^ crc_fb;
                    lsb_sr <= {din_s2, lsb_sr[63:1]};
                    msb_sr <= {msb_sr[22:0], din_s2};
                  end else begin
                    crc_rx <= {crc_rx[3:0], din_s2};
                  end
                  if (rx_next == f_w) rx_done <= 1'b1;
                end
              end
            end
          end

          // -- t_D: counter from the RE that carries the start bit to its rising edge (2.1.2) --
          if (kind == K_MEAS) begin
            if (fe_n >= 16'd9 && !din_s2) meas_low <= 1'b1;
            if (meas_low && !meas_cap && din_s2 && !din_prev) begin
              meas_cap <= 1'b1;
              meas_val <= tdc;
            end
          end

          if (!clk_run && rx_done) begin
            samp_on <= 1'b0;
            st <= ST_EVAL;
          end
        end

        // -- one frame is over: report it and choose the next --
        ST_EVAL: begin
          st <= ST_WAIT;
          gap <= T_REC;
          use_cycle <= 1'b0;
          case (kind)
            K_MEAS: begin
              if (crc_ok && meas_cap) meas_arr[meas_n[MI_W-1:0]] <= meas_val;
              else begin
                round_bad <= 1'b1;
                crc_error <= 1'b1;
              end
              if (meas_n == N_MEAS[7:0] - 8'd1) st <= ST_CALC;
              else meas_n <= meas_n + 8'd1;
            end
            K_POS: begin
              if (crc_ok) begin
                position <= lsb_sr >> (64 - POS_BITS);
                position_valid <= 1'b1;
              end else crc_error <= 1'b1;
              pos_n <= pos_n + 16'd1;
              if (pos_n + 16'd1 >= N_POS[15:0]) begin
                kind <= K_SEL;
                gap <= T_B;
              end else if (DEFECT == 2 && crc_ok) begin
                gap <= T_SHORT;
              end else begin
                use_cycle <= 1'b1;
              end
            end
            K_SEL: begin
              if (crc_ok && msb_sr == 24'hA1_0000) begin  // the selection is echoed
                kind <= K_PAR;
                gap <= T_B;
              end else begin
                crc_error <= 1'b1;
                st <= ST_DONE;
              end
            end
            default: begin
              if (crc_ok && msb_sr[23:16] == 8'h0D) begin
                param_value <= msb_sr[15:0];
                param_valid <= 1'b1;
              end else crc_error <= 1'b1;
              st <= ST_DONE;
            end
          endcase
        end

        // -- N_MEAS values in: accept their mean, or measure again --
        ST_CALC: begin
          st <= ST_WAIT;
          meas_n <= 8'd0;
          round_bad <= 1'b0;
          if (!round_bad && spread_ok) begin
            t_d <= mean[15:0];
            t_d_valid <= 1'b1;
            kind <= (N_POS == 0) ? K_SEL : K_POS;
            if (N_POS == 0) gap <= T_B;
          end else if (meas_round + 8'd1 < MEAS_ROUNDS[7:0]) begin
            meas_round <= meas_round + 8'd1;
          end else begin
            st <= ST_DONE;  // no trustworthy t_D: no compensated frames
          end
        end

        default: begin  // ST_DONE
          done <= 1'b1;
        end
      endcase
    end
  end

endmodule

`default_nettype wire
