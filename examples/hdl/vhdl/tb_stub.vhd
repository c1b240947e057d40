-- tb_stub: endat_master against encoder_stub over a cable modelled as pure transport delays,
-- the VHDL twin of examples/hdl/verilog/tb_stub.v. Passes when every position the master
-- reports is the one the stub sent, no frame fails, and word 13 reads back; a failure ends the
-- run with severity failure (non-zero exit status).
--   ghdl -r --std=08 tb_stub -gDEFECT=0 -gT_RTD_NS=700 [--vcd=wires.vcd]
library ieee;
use ieee.std_logic_1164.all;
use ieee.numeric_std.all;
use std.textio.all;

entity tb_stub is
  generic (
    DEFECT     : integer := 0;
    -- Round trip at the master's pins, CLOCK out to DATA back: 50 m at t_D max =
    -- 0.2 us + 0.01 us/m (D297403 2.3.2). The stub's own CLOCK-to-DATA delay is part of it.
    T_RTD_NS   : integer := 700;
    T_ENC_NS   : integer := 20;
    POS_BITS   : integer := 25;
    N_POS      : integer := 8;
    F_C_HZ     : integer := 8_000_000;
    MEAS_HZ    : integer := 200_000;
    N_MEAS     : integer := 3;
    CYCLE_US   : integer := 62;
    TIMEOUT_MS : integer := 50
  );
end entity tb_stub;

architecture sim of tb_stub is
  -- The master's output pads: line events then never coincide with a sys_clk edge, so Verilog
  -- and VHDL simulators resolve them alike.
  constant T_PAD   : time := 1 ns;
  constant T_CABLE : time := maximum(0, T_RTD_NS - T_ENC_NS) * 500 ps;  -- one way

  signal sys_clk : std_logic := '0';
  signal rst     : std_logic := '1';
  signal m_clock, m_out, m_oe, m_data : std_logic;
  signal position_valid, crc_error, param_valid, done : std_logic;
  signal position    : std_logic_vector(63 downto 0);
  signal param_value : std_logic_vector(15 downto 0);

  signal p_clock : std_logic := '1';  -- master pins
  signal p_out, p_oe : std_logic := '0';
  signal e_clock : std_logic := '1';  -- the master's drive at the encoder's pins
  signal e_mout, e_moe : std_logic := '0';
  signal enc_out, enc_oe : std_logic;
  signal m_eout : std_logic := '0';   -- the encoder's drive at the master's pins
  signal m_eoe  : std_logic := '1';
  signal e_data : std_logic;

  signal stub_position : std_logic_vector(63 downto 0);
  signal stub_21, stub_22, stub_param : natural;

  signal finished : boolean := false;
begin

  sys_clk <= not sys_clk after 6.25 ns when not finished;  -- 80 MHz

  dut : entity work.endat_master
    generic map (
      F_C_HZ => F_C_HZ, MEAS_HZ => MEAS_HZ, POS_BITS => POS_BITS, N_MEAS => N_MEAS,
      N_POS => N_POS, CYCLE_US => CYCLE_US, DEFECT => DEFECT)
    port map (
      sys_clk => sys_clk, rst => rst, data_in => m_data, endat_clock => m_clock,
      data_out => m_out, data_oe => m_oe, position => position, position_valid => position_valid,
      crc_error => crc_error, param_value => param_value, param_valid => param_valid, done => done);

  -- ---- line: transport delays (every edge travels, however short the pulse) ----
  p_clock <= transport m_clock after T_PAD;
  p_out   <= transport m_out after T_PAD;
  p_oe    <= transport m_oe after T_PAD;
  e_clock <= transport p_clock after T_CABLE;
  e_mout  <= transport p_out after T_CABLE;
  e_moe   <= transport p_oe after T_CABLE;
  m_eout  <= transport enc_out after T_CABLE;
  m_eoe   <= transport enc_oe after T_CABLE;
  -- Undriven DATA reads HIGH (fail-safe receivers, docs/model.md §11).
  e_data <= enc_out when enc_oe = '1' else e_mout when e_moe = '1' else '1';
  m_data <= p_out when p_oe = '1' else m_eout when m_eoe = '1' else '1';

  stub : entity work.encoder_stub
    generic map (POS_BITS => POS_BITS, T_OUT => T_ENC_NS * 1 ns)
    port map (
      clock => e_clock, data_in => e_data, data_out => enc_out, data_oe => enc_oe,
      last_position_22 => stub_position, frames_21 => stub_21, frames_22 => stub_22,
      frames_param => stub_param);

  -- ---- checks ----
  check : process
    variable got_pos, got_crc, got_par, errors : natural := 0;  -- (VHDL names ignore case)
    variable l : line;
    constant WORD13 : std_logic_vector(15 downto 0) := x"8000" or std_logic_vector(to_unsigned(POS_BITS, 16));
  begin
    assert T_RTD_NS >= T_ENC_NS
      report "FAIL tb_stub: T_RTD_NS must include the stub's T_ENC_NS" severity failure;
    for i in 1 to 8 loop
      wait until rising_edge(sys_clk);
    end loop;
    rst <= '0';
    loop
      wait until rising_edge(sys_clk) or done = '1' for TIMEOUT_MS * 1 ms;
      if now >= TIMEOUT_MS * 1 ms then
        report "FAIL tb_stub DEFECT=" & integer'image(DEFECT) & ": timeout, done never rose" severity failure;
      end if;
      if done = '1' then
        exit;
      end if;
      if position_valid = '1' then
        got_pos := got_pos + 1;
        if position /= stub_position then
          errors := errors + 1;
          write(l, time'image(now) & ": position " & to_hstring(position) & ", the stub sent " & to_hstring(stub_position));
          writeline(output, l);
        end if;
      end if;
      if crc_error = '1' then
        got_crc := got_crc + 1;
        write(l, time'image(now) & ": crc_error (the stub sent position " & to_hstring(stub_position) & ")");
        writeline(output, l);
      end if;
      if param_valid = '1' then
        got_par := got_par + 1;
        if param_value /= WORD13 then
          errors := errors + 1;
          write(l, time'image(now) & ": word 13 = " & to_hstring(param_value) & ", expected " & to_hstring(WORD13));
          writeline(output, l);
        end if;
      end if;
    end loop;
    wait for 1 us;
    write(l, "tb_stub DEFECT=" & integer'image(DEFECT) & " RTD=" & integer'image(T_RTD_NS) & " ns: " &
             integer'image(got_pos) & " positions, " & integer'image(got_crc) & " crc_error, " &
             integer'image(got_par) & " parameter reads; stub frames 2.1 " & integer'image(stub_21) &
             ", 2.2 " & integer'image(stub_22) & ", parameter " & integer'image(stub_param) &
             "; sim time " & to_string(now, us));
    writeline(output, l);
    if errors = 0 and got_crc = 0 and got_pos = N_POS and got_par = 1 then
      write(l, "PASS tb_stub DEFECT=" & integer'image(DEFECT));
      writeline(output, l);
      finished <= true;  -- the clock stops, nothing else is scheduled: the run ends, exit 0
      wait;
    end if;
    report "FAIL tb_stub DEFECT=" & integer'image(DEFECT) severity failure;
    wait;
  end process;

end architecture sim;
