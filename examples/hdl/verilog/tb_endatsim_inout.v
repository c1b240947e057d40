// tb_endatsim_inout: tb_endatsim with DATA as one inout net, as a master with an inout pad sees
// it. The master drives the net strongly while data_oe is on; endatsim's level at the master's
// receiver goes onto the same net weakly, so the bridge (+endatsim_data) tells the master's
// drive from the line's by strength.
`timescale 1ns / 1ps
`default_nettype none

module tb_endatsim_inout;
  parameter integer DEFECT = 0;

  reg sys_clk = 1'b0;
  always #6.25 sys_clk = ~sys_clk;  // 80 MHz
  reg rst = 1'b1;
  reg data_from_line = 1'b1;  // written by endatsim

  wire data;  // the inout DATA
  wire endat_clock, data_out, data_oe, position_valid, crc_error, param_valid, done;
  wire [63:0] position;
  wire [15:0] param_value;
  assign data = data_oe ? data_out : 1'bz;
  assign (weak1, weak0) data = data_from_line;

  endat_master #(.DEFECT(DEFECT)) dut (
      .sys_clk(sys_clk), .rst(rst), .data_in(data), .endat_clock(endat_clock), .data_out(data_out),
      .data_oe(data_oe), .position(position), .position_valid(position_valid), .crc_error(crc_error),
      .param_value(param_value), .param_valid(param_valid), .done(done));

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
    #100_000;
    $finish;
  end
endmodule

`default_nettype wire
