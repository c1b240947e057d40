// tb_stub: endat_master against encoder_stub over a cable modelled as pure transport delays.
// Passes when every position the master reports is the one the stub sent, no frame fails, and
// word 13 reads back. Exit status: 0 on PASS, 1 ($fatal) on FAIL.
//   iverilog -g2012 -s tb_stub -P tb_stub.DEFECT=0 -P tb_stub.T_RTD_NS=700 ...
//   vvp sim.vvp [+vcd=wires.vcd]   (CLOCK, DATA and both enables at the encoder's connector
//   (e_*, enc_oe) and at the master's (p_*, m_data),
//   for `endatsim check wires.vcd --clock e_clock --data e_data --data-enable enc_oe
//   --master-data-enable e_moe --clock-to-data "20 ns" --cable 50`)
`timescale 1ns / 1ps
`default_nettype none

module tb_stub;
  parameter integer DEFECT = 0;
  // Round trip at the master's pins, CLOCK out to DATA back: 50 m at t_D max =
  // 0.2 us + 0.01 us/m (D297403 2.3.2). The stub's own CLOCK-to-DATA delay is part of it.
  parameter real T_RTD_NS = 700.0;
  parameter real T_ENC_NS = 20.0;
  parameter integer POS_BITS = 25;
  parameter integer N_POS = 8;
  parameter integer F_C_HZ = 8_000_000;
  parameter integer MEAS_HZ = 200_000;
  parameter integer N_MEAS = 3;
  parameter integer CYCLE_US = 62;
  parameter real TIMEOUT_MS = 50.0;
  // The master's output pads: line events then never coincide with a sys_clk edge, so Verilog
  // and VHDL simulators resolve them alike.
  localparam real T_PAD_NS = 1.0;
  localparam real T_CABLE_NS = (T_RTD_NS > T_ENC_NS) ? (T_RTD_NS - T_ENC_NS) / 2.0 : 0.0;  // one way

  reg sys_clk = 1'b0;
  always #6.25 sys_clk = ~sys_clk;  // 80 MHz
  reg rst = 1'b1;

  wire m_clock, m_out, m_oe, position_valid, crc_error, param_valid, done;
  wire [63:0] position;
  wire [15:0] param_value;
  wire m_data;  // DATA at the master's pins

  endat_master #(
      .F_C_HZ(F_C_HZ),
      .MEAS_HZ(MEAS_HZ),
      .POS_BITS(POS_BITS),
      .N_MEAS(N_MEAS),
      .N_POS(N_POS),
      .CYCLE_US(CYCLE_US),
      .DEFECT(DEFECT)
  ) dut (
      .sys_clk(sys_clk),
      .rst(rst),
      .data_in(m_data),
      .endat_clock(m_clock),
      .data_out(m_out),
      .data_oe(m_oe),
      .position(position),
      .position_valid(position_valid),
      .crc_error(crc_error),
      .param_value(param_value),
      .param_valid(param_valid),
      .done(done)
  );

  // ---- line: transport delays (every edge travels, however short the pulse) ----
  reg p_clock = 1'b1, p_out = 1'b0, p_oe = 1'b0;  // master pins
  always @(m_clock) p_clock <= #(T_PAD_NS) m_clock;
  always @(m_out) p_out <= #(T_PAD_NS) m_out;
  always @(m_oe) p_oe <= #(T_PAD_NS) m_oe;

  reg e_clock = 1'b1, e_mout = 1'b0, e_moe = 1'b0;  // the master's drive at the encoder's pins
  always @(p_clock) e_clock <= #(T_CABLE_NS) p_clock;
  always @(p_out) e_mout <= #(T_CABLE_NS) p_out;
  always @(p_oe) e_moe <= #(T_CABLE_NS) p_oe;

  wire enc_out, enc_oe;
  reg m_eout = 1'b0, m_eoe = 1'b1;  // the encoder's drive at the master's pins
  always @(enc_out) m_eout <= #(T_CABLE_NS) enc_out;
  always @(enc_oe) m_eoe <= #(T_CABLE_NS) enc_oe;

  // Undriven DATA reads HIGH (fail-safe receivers, docs/model.md §11).
  wire e_data = enc_oe ? enc_out : (e_moe ? e_mout : 1'b1);
  assign m_data = p_oe ? p_out : (m_eoe ? m_eout : 1'b1);

  wire [63:0] stub_position;
  integer stub_21, stub_22, stub_param;
  encoder_stub #(
      .POS_BITS(POS_BITS),
      .T_OUT_NS(T_ENC_NS)
  ) stub (
      .clock(e_clock),
      .data_in(e_data),
      .data_out(enc_out),
      .data_oe(enc_oe),
      .last_position_22(stub_position),
      .frames_21(stub_21),
      .frames_22(stub_22),
      .frames_param(stub_param)
  );

  // ---- checks ----
  integer n_pos = 0, n_crc = 0, n_par = 0, errors = 0;
  always @(posedge sys_clk) begin
    if (!rst) begin
      if (position_valid) begin
        n_pos = n_pos + 1;
        if (position !== stub_position) begin
          errors = errors + 1;
          $display("%0.3f us: position %h, the stub sent %h", $realtime / 1000.0, position, stub_position);
        end
      end
      if (crc_error) begin
        n_crc = n_crc + 1;
        $display("%0.3f us: crc_error (the stub sent position %h)", $realtime / 1000.0, stub_position);
      end
      if (param_valid) begin
        n_par = n_par + 1;
        if (param_value !== (16'h8000 | POS_BITS[15:0])) begin
          errors = errors + 1;
          $display("%0.3f us: word 13 = %h, expected %h", $realtime / 1000.0, param_value,
                   16'h8000 | POS_BITS[15:0]);
        end
      end
    end
  end

  reg [1023:0] vcd_file;
  initial begin
    if (T_RTD_NS < T_ENC_NS) begin
      $display("FAIL tb_stub: T_RTD_NS (%0.1f) must include the stub's T_ENC_NS (%0.1f)", T_RTD_NS, T_ENC_NS);
      $fatal(1);
    end
    if ($value$plusargs("vcd=%s", vcd_file)) begin
      $dumpfile(vcd_file);
      $dumpvars(0, e_clock, e_data, enc_oe, e_moe, p_clock, p_out, p_oe, m_data);
    end
    repeat (8) @(posedge sys_clk);
    rst = 1'b0;
  end

  initial begin
    #(TIMEOUT_MS * 1.0e6);
    $display("FAIL tb_stub DEFECT=%0d: timeout, done never rose", DEFECT);
    $fatal(1);
  end

  initial begin
    @(posedge done);
    #1000;
    $display("tb_stub DEFECT=%0d RTD=%0.1f ns: t_D measured %0d cycles (valid %0d), %0d positions, %0d crc_error, %0d parameter reads; stub frames 2.1 %0d, 2.2 %0d, parameter %0d; sim time %0.3f ms",
             DEFECT, T_RTD_NS, dut.t_d, dut.t_d_valid, n_pos, n_crc, n_par, stub_21, stub_22, stub_param,
             $realtime / 1.0e6);
    if (errors == 0 && n_crc == 0 && n_pos == N_POS && n_par == 1) begin
      $display("PASS tb_stub DEFECT=%0d", DEFECT);
      $finish;
    end else begin
      $display("FAIL tb_stub DEFECT=%0d", DEFECT);
      $fatal(1);
    end
  end

endmodule

`default_nettype wire
