-- tb_endatsim: endat_master for co-simulation with endatsim's encoder and cable through the VPI
-- bridge, the VHDL twin of examples/hdl/verilog/tb_endatsim.v. The bridge watches endat_clock,
-- data_out and data_oe and writes data_in_from_line, the DATA level at the master's pins.
-- VHDL has no user system tasks: position, position_valid, param_value, param_valid and done
-- are signals of this testbench for the bridge to read. The run ends 100 us after done.
--   ghdl -r --std=08 tb_endatsim -gDEFECT=1
library ieee;
use ieee.std_logic_1164.all;

entity tb_endatsim is
  generic (
    DEFECT   : integer := 0;
    F_C_HZ   : integer := 8_000_000;
    MEAS_HZ  : integer := 200_000;
    POS_BITS : integer := 25;
    N_MEAS   : integer := 3;
    N_POS    : integer := 8;
    CYCLE_US : integer := 62
  );
end entity tb_endatsim;

architecture sim of tb_endatsim is
  signal sys_clk           : std_logic := '0';
  signal rst               : std_logic := '1';
  signal data_in_from_line : std_logic := '1';  -- written by endatsim
  signal endat_clock, data_out, data_oe : std_logic;
  signal position_valid, crc_error, param_valid, done : std_logic;
  signal position    : std_logic_vector(63 downto 0);
  signal param_value : std_logic_vector(15 downto 0);
begin

  sys_clk <= not sys_clk after 6.25 ns;  -- 80 MHz: an exact 12.5 ns period

  dut : entity work.endat_master
    generic map (
      F_C_HZ => F_C_HZ, MEAS_HZ => MEAS_HZ, POS_BITS => POS_BITS, N_MEAS => N_MEAS,
      N_POS => N_POS, CYCLE_US => CYCLE_US, DEFECT => DEFECT)
    port map (
      sys_clk => sys_clk, rst => rst, data_in => data_in_from_line, endat_clock => endat_clock,
      data_out => data_out, data_oe => data_oe, position => position,
      position_valid => position_valid, crc_error => crc_error, param_value => param_value,
      param_valid => param_valid, done => done);

  control : process
  begin
    for i in 1 to 8 loop
      wait until rising_edge(sys_clk);
    end loop;
    rst <= '0';
    wait until done = '1';
    wait for 100 us;  -- the last frame's recovery time is over
    std.env.finish;
  end process;

end architecture sim;
