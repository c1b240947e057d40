-- encoder_stub: a simple behavioural EnDat 2.2 encoder for tb_stub (not synthesizable), the VHDL
-- twin of examples/hdl/verilog/encoder_stub.v. It answers "Encoder send position values" (2.1),
-- "... with additional data" (2.2, none selected), "Selection of memory area" and "Encoder send
-- parameters"; word 13 of MRS A1h holds the position width as D297403 3.5.6 stores it
-- (8000h | bits). It checks no timing: a stub as a designer would write one, to be compared
-- with endatsim's encoder. Its ports are the encoder's pins; the testbench adds the cable.
library ieee;
use ieee.std_logic_1164.all;
use ieee.numeric_std.all;

entity encoder_stub is
  generic (
    POS_BITS  : integer := 25;
    T_CAL     : time := 5 us;    -- FE1 -> start bit (D297403 2.3.2 t_cal)
    T_AC      : time := 50 us;   -- last payload bit -> start bit of a parameter answer
    T_M       : time := 10 us;   -- CLOCK HIGH this long ends a frame (t_m)
    T_OUT     : time := 20 ns;   -- CLOCK edge in -> DATA out (logic and transceivers)
    POS_START : std_logic_vector(63 downto 0) := x"0000000001234567";
    POS_STEP  : std_logic_vector(63 downto 0) := x"0000000000102031"  -- changes many bits
  );
  port (
    clock            : in  std_logic;
    data_in          : in  std_logic;
    data_out         : out std_logic := '0';
    data_oe          : out std_logic := '1';  -- idle: DATA driven LOW
    last_position_22 : out std_logic_vector(63 downto 0) := (others => '0');
    frames_21        : out natural := 0;
    frames_22        : out natural := 0;
    frames_param     : out natural := 0
  );
end entity encoder_stub;

architecture behaviour of encoder_stub is

  function mask return unsigned is
    variable m : unsigned(63 downto 0) := (others => '0');
  begin
    for i in 0 to 63 loop
      if i < POS_BITS then m(i) := '1'; end if;
    end loop;
    return m;
  end function;

  function crc_step(c : std_logic_vector(4 downto 0); b : std_logic) return std_logic_vector is
  begin  -- D297403 A4: x^5 + x^3 + x + 1
    if (b xor c(4)) = '1' then
      return (c(3 downto 0) & '0') xor "01011";
    end if;
    return c(3 downto 0) & '0';
  end function;

  type state_t is (S_IDLE, S_HEAD, S_WAIT, S_SEND, S_END, S_NONE);

begin

  process (clock)
    variable state      : state_t := S_IDLE;
    variable fe, re     : integer := 0;
    variable turn       : integer := 9;
    variable first_re   : integer := 11;
    variable width, idx : integer := 0;
    variable t_fe1, t_last_re, t_ready, t_hi_max : time := 0 ns;
    variable mode       : std_logic_vector(5 downto 0);
    variable payload    : std_logic_vector(23 downto 0);
    variable payload_cmd : boolean := false;
    variable ans        : std_logic_vector(0 to 127);  -- bit 0 goes first on the wire
    variable pos        : unsigned(63 downto 0) := unsigned(POS_START) and mask;
    variable latched    : unsigned(63 downto 0) := (others => '0');
    variable mrs        : std_logic_vector(7 downto 0) := x"00";
    variable value      : std_logic_vector(15 downto 0);
    variable n21, n22, npar : natural := 0;

    -- Appends the CRC over bits 1 .. nbits (everything after the start bit).
    procedure add_crc(nbits : integer) is
      variable c : std_logic_vector(4 downto 0) := "11111";  -- A4.4.1: preset to 1
    begin
      for k in 1 to nbits loop
        c := crc_step(c, ans(k));
      end loop;
      c := not c;  -- sent inverted, MSB first
      for k in 0 to 4 loop
        ans(nbits + 1 + k) := c(4 - k);
      end loop;
      width := nbits + 6;
    end procedure;

    procedure position_answer(v22 : boolean) is
      variable n : integer := 2;
    begin
      ans := (others => '0');
      ans(0) := '1';  -- S
      ans(1) := '0';  -- F1: no error
      if v22 then
        ans(2) := '1';  -- F2 is low-active
        n := 3;
      end if;
      for k in 0 to POS_BITS - 1 loop
        ans(n + k) := latched(k);  -- LSB first
      end loop;
      add_crc(n + POS_BITS - 1);
    end procedure;

    procedure parameter_answer(addr : std_logic_vector(7 downto 0); par : std_logic_vector(15 downto 0)) is
    begin
      ans := (others => '0');
      ans(0) := '1';
      for k in 0 to 7 loop
        ans(1 + k) := addr(7 - k);
      end loop;
      for k in 0 to 15 loop
        ans(9 + k) := par(15 - k);
      end loop;
      add_crc(24);
    end procedure;

    -- Transport delays: each edge comes out, however short the bit.
    procedure drive(oe, d : std_logic) is
    begin
      data_oe <= transport oe after T_OUT;
      data_out <= transport d after T_OUT;
    end procedure;

  begin
    if falling_edge(clock) then
      -- A new frame: after idle, after CLOCK HIGH for t_m, or after the answer when CLOCK stayed
      -- HIGH longer than twice the frame's longest HIGH phase (more pulses at the frame's own
      -- rate are extra clocks, not a new frame).
      if state = S_IDLE or (now - t_last_re) >= T_M or
         (state = S_END and (now - t_last_re) > 2 * t_hi_max) then
        -- FE1: latch the position, release DATA
        state := S_HEAD;
        fe := 1;
        re := 0;
        turn := 9;
        mode := (others => '0');
        payload := (others => '0');
        payload_cmd := false;
        t_fe1 := now;
        t_hi_max := 0 ns;
        latched := pos;
        data_oe <= transport '0' after T_OUT;
      else
        fe := fe + 1;
        if now - t_last_re > t_hi_max then
          t_hi_max := now - t_last_re;
        end if;
        if fe = turn then  -- take DATA back, LOW until the start bit
          drive('1', '0');
        end if;
      end if;
    elsif rising_edge(clock) then
      t_last_re := now;
      re := re + 1;
      case state is
        when S_HEAD =>
          if re >= 3 and re <= 8 then
            mode := mode(4 downto 0) & data_in;
          elsif payload_cmd and re >= 9 and re <= 32 then
            payload := payload(22 downto 0) & data_in;
          end if;
          if re = 8 then
            if mode = "000111" or mode = "111000" then
              position_answer(mode = "111000");
              if mode = "111000" then
                last_position_22 <= std_logic_vector(latched);
                n22 := n22 + 1;
                frames_22 <= n22;
              else
                n21 := n21 + 1;
                frames_21 <= n21;
              end if;
              pos := (pos + unsigned(POS_STEP)) and mask;
              state := S_WAIT;
              first_re := 11;
              t_ready := t_fe1 + T_CAL;
            elsif mode = "001110" or mode = "100011" then
              payload_cmd := true;
              turn := 33;
            else
              state := S_NONE;  -- not supported: no start bit
            end if;
          end if;
          if payload_cmd and re = 32 then
            if mode = "001110" then
              mrs := payload(23 downto 16);
              parameter_answer(payload(23 downto 16), payload(15 downto 0));
            else
              if mrs = x"A1" and payload(23 downto 16) = x"0D" then
                value := x"8000" or std_logic_vector(to_unsigned(POS_BITS, 16));
              else
                value := x"0000";
              end if;
              parameter_answer(payload(23 downto 16), value);
            end if;
            npar := npar + 1;
            frames_param <= npar;
            state := S_WAIT;
            first_re := 35;
            t_ready := now + T_AC;
          end if;
        when S_WAIT =>
          if re >= first_re and now >= t_ready then
            drive('1', '1');  -- start bit
            idx := 1;
            state := S_SEND;
          end if;
        when S_SEND =>
          if idx < width then
            drive('1', ans(idx));
            idx := idx + 1;
          else
            drive('1', '1');  -- end of data: HIGH
            state := S_END;
          end if;
        when others =>
          null;
      end case;
    end if;
  end process;

end architecture behaviour;
