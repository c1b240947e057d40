-- tb_endatsim_inout: tb_endatsim with DATA as one inout std_logic, as a master with an inout pad
-- sees it. The master drives '0'/'1' while data_oe is on; endatsim's level at the master's
-- receiver goes onto the same signal as 'L'/'H', so the bridge (+endatsim_data) tells the
-- master's drive from the line's by std_logic's strength.
library ieee;
use ieee.std_logic_1164.all;

entity tb_endatsim_inout is
  generic (DEFECT : integer := 0);
end entity tb_endatsim_inout;

architecture sim of tb_endatsim_inout is
  signal sys_clk        : std_logic := '0';
  signal rst            : std_logic := '1';
  signal data_from_line : std_logic := '1';  -- written by endatsim
  signal data           : std_logic;         -- the inout DATA
  signal data_rx        : std_logic;
  signal endat_clock, data_out, data_oe : std_logic;
  signal position_valid, crc_error, param_valid, done : std_logic;
  signal position    : std_logic_vector(63 downto 0);
  signal param_value : std_logic_vector(15 downto 0);
begin
  sys_clk <= not sys_clk after 6.25 ns;
  data <= data_out when data_oe = '1' else 'Z';
  data <= 'H' when data_from_line = '1' else 'L';
  data_rx <= to_x01(data);

  dut : entity work.endat_master
    generic map (DEFECT => DEFECT)
    port map (
      sys_clk => sys_clk, rst => rst, data_in => data_rx, endat_clock => endat_clock,
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
    wait for 100 us;
    std.env.finish;
  end process;
end architecture sim;
