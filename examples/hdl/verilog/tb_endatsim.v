// tb_endatsim: endat_master for co-simulation with endatsim's encoder and cable through the VPI
// bridge. The bridge watches endat_clock, data_out and data_oe (dut.*) and writes
// data_in_from_line, the DATA level at the master's pins; $endatsim_position and
// $endatsim_parameter are the bridge's system tasks. Without the bridge this elaborates only
// up to those two tasks.
//   iverilog -g2012 -s tb_endatsim -P tb_endatsim.DEFECT=1 ...
`timescale 1ns / 1ps
`default_nettype none

module tb_endatsim;
  parameter integer DEFECT = 0;
  parameter integer F_C_HZ = 8_000_000;
  parameter integer MEAS_HZ = 200_000;
  parameter integer POS_BITS = 25;
  parameter integer N_MEAS = 3;
  parameter integer N_POS = 8;
  parameter integer CYCLE_US = 62;

  reg sys_clk = 1'b0;
  always #6.25 sys_clk = ~sys_clk;  // 80 MHz: an exact 12.5 ns period
  reg rst = 1'b1;
  reg data_in_from_line = 1'b1;  // written by endatsim through VPI

  wire endat_clock, data_out, data_oe, position_valid, crc_error, param_valid, done;
  wire [63:0] position;
  wire [15:0] param_value;

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
      .data_in(data_in_from_line),
      .endat_clock(endat_clock),
      .data_out(data_out),
      .data_oe(data_oe),
      .position(position),
      .position_valid(position_valid),
      .crc_error(crc_error),
      .param_value(param_value),
      .param_valid(param_valid),
      .done(done)
  );

  initial begin
    repeat (8) @(posedge sys_clk);
    rst = 1'b0;
  end

  always @(posedge sys_clk) begin
    if (position_valid) $endatsim_position(position);
    if (param_valid) $endatsim_parameter(param_value);
  end

  initial begin
    @(posedge done);
    #100_000;  // 100 us: the last frame's recovery time is over
    $finish;
  end

endmodule

`default_nettype wire
