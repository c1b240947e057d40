-- endat_master: a small synthesizable EnDat 2.2 master (HEIDENHAIN D297403), the VHDL twin of
-- examples/hdl/verilog/endat_master.v: same generics, ports, sequence and timing.
--
-- After reset it
--   1. measures the propagation delay t_D with N_MEAS "Encoder send position values" frames
--      (000111) at MEAS_HZ (D297403 2.1.2),
--   2. reads N_POS positions with "Encoder send position values with additional data"
--      (111000, no additional data selected) at F_C_HZ, sampling each bit t_D after the edge
--      that launched it (D297403 2.3),
--   3. reads word 13 of the encoder manufacturer's parameters (MRS A1h, address 0Dh) with the
--      EnDat 2.1 commands "Selection of memory area" and "Encoder send parameters",
--   4. raises done and leaves CLOCK HIGH.
--
-- Frame positions follow the spec's figures: FEk / REk is the k-th falling / rising CLOCK edge of
-- a frame, FE1 opens it. The master drives DATA from FE2 (a 0), sends the mode bits on FE3..FE8
-- (and a 2.1 payload of 8 + 16 bits on FE9..FE32), and releases DATA on FE9 (FE33).
-- The encoder's bit after REk is "slot k".
--
-- DEFECT (each breaks one rule of D297403 2.3.2 on purpose, everything else stays right):
--   1: t_ST 1 us instead of 2 us at 8 MHz (note 8)
--   2: only ~2 us of CLOCK HIGH between position reads (t_m + t_R, notes 3, 9)
--   3: no delay measurement, position reads at 2 MHz sampled at the falling edge (f_c against
--      the cable without compensation, 2.1.1 / 2.1.2)
--
-- SYS_HZ must be at least 8 x F_C_HZ: sys_clk is the t_D counter, and D297403 2.1.2 wants it at
-- eight times the compensated f_c or more (80 MHz for 8 MHz: 12.5 ns counts, T/8 = 15.6 ns).
library ieee;
use ieee.std_logic_1164.all;
use ieee.numeric_std.all;

entity endat_master is
  generic (
    SYS_HZ   : integer := 80_000_000;
    F_C_HZ   : integer := 8_000_000;
    MEAS_HZ  : integer := 200_000;
    POS_BITS : integer := 25;
    N_MEAS   : integer := 3;
    N_POS    : integer := 8;
    CYCLE_US : integer := 62;
    DEFECT   : integer := 0
  );
  port (
    sys_clk        : in  std_logic;
    rst            : in  std_logic;
    data_in        : in  std_logic;
    endat_clock    : out std_logic;
    data_out       : out std_logic;
    data_oe        : out std_logic;
    position       : out std_logic_vector(63 downto 0);
    position_valid : out std_logic;
    crc_error      : out std_logic;
    param_value    : out std_logic_vector(15 downto 0);
    param_valid    : out std_logic;
    done           : out std_logic
  );
end entity endat_master;

architecture rtl of endat_master is

  function pick(c : boolean; a, b : integer) return integer is
  begin
    if c then return a; else return b; end if;
  end function;

  -- ---- timing, in sys_clk cycles ----
  -- Periods round up, so a clock is never faster than asked; minimum times round up too.
  constant CYC_US       : integer := (SYS_HZ + 999_999) / 1_000_000;
  constant F_POS        : integer := pick(DEFECT = 3, 2_000_000, F_C_HZ);
  constant P_POS        : integer := (SYS_HZ + F_POS - 1) / F_POS;
  constant P_MEAS       : integer := (SYS_HZ + MEAS_HZ - 1) / MEAS_HZ;
  -- D297403 2.3.2 note 8: t_ST 2 us for f_c 2 .. 8 MHz (the first LOW phase, FE1 -> RE1).
  constant T_ST         : integer := pick(DEFECT = 1, 1, 2) * CYC_US;
  -- D297403 2.3.2: t_m max 30 us + t_R 0.5 us, + 0.5 us so rounding never lands on the limit.
  -- The same wait covers A2 (after an error handling wait the maximum t_m) and the start.
  constant T_REC        : integer := 31 * CYC_US;
  constant T_SHORT      : integer := 2 * CYC_US;  -- DEFECT 2 only
  -- D297403 2.3.2 t_b > 1 ms before a 2.1 parameter frame.
  constant T_B          : integer := 1100 * CYC_US;
  constant T_CYCLE      : integer := CYCLE_US * CYC_US;
  -- Polling limits (2.3.2: polling must not depend on t_cal): t_cal max 1 ms from FE1, t_ac max
  -- 12 ms from the last payload bit; each with margin.
  constant T_CAL_GIVEUP : integer := 1100 * CYC_US;
  constant T_AC_GIVEUP  : integer := 13_000 * CYC_US;
  constant W_POS21      : integer := POS_BITS + 7;  -- S F1 position CRC
  constant W_POS22      : integer := POS_BITS + 8;  -- S F1 F2 position CRC
  constant W_PAR        : integer := 30;            -- S address(8) parameter(16) CRC
  constant MEAS_ROUNDS  : integer := 3;  -- rounds before giving up on a delay that will not settle

  type kind_t is (K_MEAS, K_POS, K_SEL, K_PAR);
  type state_t is (ST_WAIT, ST_FRAME, ST_EVAL, ST_CALC, ST_DONE);
  type meas_arr_t is array (0 to N_MEAS - 1) of unsigned(15 downto 0);

  function first_kind_of(d : integer) return kind_t is
  begin
    if d = 3 then return K_POS; else return K_MEAS; end if;  -- DEFECT 3 measures nothing
  end function;
  constant FIRST_KIND : kind_t := first_kind_of(DEFECT);

  -- DATA input synchronizer: its latency is inside every t_D count and every sampling instant
  -- alike, so it cancels.
  signal din_s1, din_s2, din_prev : std_logic := '0';

  signal st         : state_t := ST_WAIT;
  signal kind       : kind_t := FIRST_KIND;
  signal meas_n     : integer range 0 to 255 := 0;
  signal meas_round : integer range 0 to 255 := 0;
  signal pos_n      : integer range 0 to 65535 := 0;
  signal round_bad  : std_logic := '0';
  signal meas_arr   : meas_arr_t := (others => (others => '0'));
  signal t_d        : unsigned(15 downto 0) := (others => '0');  -- measured t_D in cycles
  signal t_d_valid  : std_logic := '0';
  signal gap, since_re, since_fe1 : unsigned(31 downto 0) := (others => '0');
  signal use_cycle  : std_logic := '0';

  -- Frame engine.
  signal clk_run, abort : std_logic := '0';
  signal edge_cnt, fe_n, re_n, last_re : unsigned(15 downto 0) := (others => '0');
  signal tx_sr      : std_logic_vector(29 downto 0) := (others => '0');  -- mode bits, payload
  signal samp_on    : std_logic := '0';
  signal samp_cnt, samp_slot : unsigned(15 downto 0) := (others => '0');
  signal rx_data, rx_done, rx_fail, seen_low : std_logic := '0';
  signal hi_cnt     : unsigned(3 downto 0) := (others => '0');
  signal rx_idx     : unsigned(7 downto 0) := (others => '0');
  signal poll_cnt   : unsigned(31 downto 0) := (others => '0');
  signal crc_calc, crc_rx : std_logic_vector(4 downto 0) := (others => '0');
  signal lsb_sr     : std_logic_vector(63 downto 0) := (others => '0');  -- position, LSB first
  signal msb_sr     : std_logic_vector(23 downto 0) := (others => '0');  -- address, parameter
  -- D297403 2.1.2 counter: restarted at each RE, saved at the start bit.
  signal tdc, meas_val : unsigned(15 downto 0) := (others => '0');
  signal meas_low, meas_cap : std_logic := '0';

  signal clk_o : std_logic := '1';  -- power-up values as after reset: CLOCK HIGH, DATA not driven
  signal dout_o, doe_o : std_logic := '0';

  -- ---- per-frame settings from the frame kind ----
  signal f_p, f_hi, f_lo, f_lo1, f_ds, f_rel : unsigned(15 downto 0);
  signal f_mode    : std_logic_vector(5 downto 0);
  signal f_payload : std_logic_vector(23 downto 0);
  signal f_w       : unsigned(7 downto 0);

  signal mean      : unsigned(15 downto 0);
  signal spread_ok : std_logic;
  signal crc_ok    : std_logic;
  signal crc_fb    : std_logic_vector(4 downto 0);
  signal rx_next   : unsigned(7 downto 0);
  signal wait_over : std_logic;

begin

  endat_clock <= clk_o;
  data_out    <= dout_o;
  data_oe     <= doe_o;

  settings : process (kind, t_d, t_d_valid)
    variable p, hi, lo : unsigned(15 downto 0);
    variable comp      : boolean;
  begin
    f_payload <= x"000000";
    case kind is
      when K_MEAS =>
        p := to_unsigned(P_MEAS, 16);
        f_mode <= "000111";
        f_w <= to_unsigned(W_POS21, 8);
      when K_POS =>
        p := to_unsigned(P_POS, 16);
        f_mode <= "111000";
        f_w <= to_unsigned(W_POS22, 8);
      when K_SEL =>
        p := to_unsigned(P_MEAS, 16);
        f_mode <= "001110";
        f_payload <= x"A10000";  -- MRS code A1h: encoder manufacturer's parameters, words 0..15
        f_w <= to_unsigned(W_PAR, 8);
      when K_PAR =>
        p := to_unsigned(P_MEAS, 16);
        f_mode <= "100011";
        f_payload <= x"0D0000";  -- address 0Dh: word 13, clock pulses for the position value
        f_w <= to_unsigned(W_PAR, 8);
    end case;
    hi := shift_right(p, 1);
    lo := p - hi;
    f_p <= p;
    f_hi <= hi;
    f_lo <= lo;
    if lo > to_unsigned(T_ST, 16) then
      f_lo1 <= lo;
    else
      f_lo1 <= to_unsigned(T_ST, 16);
    end if;
    -- Measurement frames are never compensated; afterwards every frame is (t_D known).
    comp := kind /= K_MEAS and t_d_valid = '1';
    -- Sample slot k at REk + f_ds: the falling edge (hi) without compensation; with it half a
    -- period after the bit's edge shows at the synchronizer output (t_d + 1, as tdc counted it).
    if comp then
      f_ds <= hi + t_d + 1;
    else
      f_ds <= hi;
    end if;
    if kind = K_SEL or kind = K_PAR then
      f_rel <= to_unsigned(33, 16);
    else
      f_rel <= to_unsigned(9, 16);
    end if;
  end process;

  -- ---- delay measurements agree within T/8 of the compensated period (D297403 2.1.2) ----
  spread : process (meas_arr)
    variable sum, dev : unsigned(31 downto 0);
    variable ok       : std_logic;
  begin
    sum := (others => '0');
    for i in 0 to N_MEAS - 1 loop
      sum := sum + resize(meas_arr(i), 32);
    end loop;
    ok := '1';
    for i in 0 to N_MEAS - 1 loop
      dev := resize(meas_arr(i) * to_unsigned(N_MEAS, 16), 32);
      if dev > sum then dev := dev - sum; else dev := sum - dev; end if;
      if shift_left(dev, 3) > to_unsigned(N_MEAS * P_POS, 32) then
        ok := '0';
      end if;
    end loop;
    spread_ok <= ok;
    mean <= resize((sum + N_MEAS / 2) / N_MEAS, 16);  -- rounded
  end process;

  crc_ok    <= '1' when rx_fail = '0' and crc_rx = not crc_calc else '0';
  crc_fb    <= "01011" when (din_s2 xor crc_calc(4)) = '1' else "00000";  -- A4: x^5 + x^3 + x + 1
  rx_next   <= rx_idx + 1;
  wait_over <= '1' when since_re >= gap and (use_cycle = '0' or since_fe1 >= to_unsigned(T_CYCLE, 32)) else '0';

  main : process (sys_clk)
    variable k : unsigned(15 downto 0);
  begin
    if rising_edge(sys_clk) then
      if rst = '1' then
        din_s1 <= '0';
        din_s2 <= '0';
        din_prev <= '0';
        st <= ST_WAIT;
        kind <= FIRST_KIND;
        meas_n <= 0;
        meas_round <= 0;
        pos_n <= 0;
        round_bad <= '0';
        meas_arr <= (others => (others => '0'));
        t_d <= (others => '0');
        t_d_valid <= '0';
        gap <= to_unsigned(T_REC, 32);  -- CLOCK HIGH first: the encoder ends any frame it was in
        since_re <= (others => '0');
        since_fe1 <= (others => '0');
        use_cycle <= '0';
        clk_run <= '0';
        abort <= '0';
        edge_cnt <= (others => '0');
        fe_n <= (others => '0');
        re_n <= (others => '0');
        last_re <= (others => '0');
        tx_sr <= (others => '0');
        samp_on <= '0';
        samp_cnt <= (others => '0');
        samp_slot <= (others => '0');
        rx_data <= '0';
        rx_done <= '0';
        rx_fail <= '0';
        seen_low <= '0';
        hi_cnt <= (others => '0');
        rx_idx <= (others => '0');
        poll_cnt <= (others => '0');
        crc_calc <= "11111";
        crc_rx <= "00000";
        lsb_sr <= (others => '0');
        msb_sr <= (others => '0');
        tdc <= (others => '0');
        meas_val <= (others => '0');
        meas_low <= '0';
        meas_cap <= '0';
        clk_o <= '1';
        dout_o <= '0';
        doe_o <= '0';
        position <= (others => '0');
        position_valid <= '0';
        crc_error <= '0';
        param_value <= (others => '0');
        param_valid <= '0';
        done <= '0';
      else
        din_s1 <= data_in;
        din_s2 <= din_s1;
        din_prev <= din_s2;
        position_valid <= '0';
        crc_error <= '0';
        param_valid <= '0';
        if since_re /= x"FFFFFFFF" then since_re <= since_re + 1; end if;
        if since_fe1 /= x"FFFFFFFF" then since_fe1 <= since_fe1 + 1; end if;
        if tdc /= x"FFFF" then tdc <= tdc + 1; end if;

        case st is
          -- CLOCK HIGH until the recovery (or t_b, or the cycle) is over, then FE1
          when ST_WAIT =>
            if wait_over = '1' then
              st <= ST_FRAME;
              clk_o <= '0';  -- FE1: the encoder latches its position, releases DATA
              clk_run <= '1';
              abort <= '0';
              edge_cnt <= f_lo1 - 1;  -- t_ST
              fe_n <= to_unsigned(1, 16);
              re_n <= (others => '0');
              last_re <= (others => '0');
              samp_on <= '0';
              rx_data <= '0';
              rx_done <= '0';
              rx_fail <= '0';
              seen_low <= '0';
              hi_cnt <= (others => '0');
              rx_idx <= (others => '0');
              poll_cnt <= (others => '0');
              crc_calc <= "11111";  -- A4.4.1: flip-flops preset to 1
              crc_rx <= "00000";
              meas_low <= '0';
              meas_cap <= '0';
              since_fe1 <= (others => '0');
            end if;

          when ST_FRAME =>
            -- polling gives up only after t_cal max / t_ac max (D297403 2.3.2); first, so that
            -- the restart at the release below takes precedence
            if rx_data = '0' and rx_done = '0' then
              poll_cnt <= poll_cnt + 1;
              if (kind = K_SEL or kind = K_PAR) then
                if poll_cnt >= to_unsigned(T_AC_GIVEUP, 32) then
                  rx_done <= '1';
                  rx_fail <= '1';
                  abort <= '1';
                end if;
              elsif poll_cnt >= to_unsigned(T_CAL_GIVEUP, 32) then
                rx_done <= '1';
                rx_fail <= '1';
                abort <= '1';
              end if;
            end if;

            -- clock generator
            if clk_run = '1' then
              if edge_cnt /= 0 then
                edge_cnt <= edge_cnt - 1;
              elsif clk_o = '1' then
                if abort = '1' or (last_re /= 0 and re_n >= last_re) then
                  -- The last pulse's RE has brought the end marker: CLOCK stays HIGH.
                  clk_run <= '0';
                else
                  clk_o <= '0';
                  k := fe_n + 1;
                  fe_n <= k;
                  edge_cnt <= f_lo - 1;
                  if k = 2 then
                    -- FE2: the master takes DATA and sends the leading 0 (D297403 2.3)
                    doe_o <= '1';
                    dout_o <= '0';
                    tx_sr <= f_mode & f_payload;
                  elsif k < f_rel then
                    dout_o <= tx_sr(29);
                    tx_sr <= tx_sr(28 downto 0) & '0';
                  elsif k = f_rel then
                    -- FE9 (FE33 after a payload): hand DATA to the encoder
                    doe_o <= '0';
                    dout_o <= '0';
                    poll_cnt <= (others => '0');  -- t_ac runs from the last payload bit
                  end if;
                end if;
              else
                clk_o <= '1';
                re_n <= re_n + 1;
                edge_cnt <= f_hi - 1;
                since_re <= (others => '0');
                tdc <= (others => '0');
                if re_n = 0 then
                  samp_on <= '1';
                  samp_cnt <= f_ds - 1;
                  samp_slot <= to_unsigned(1, 16);
                end if;
              end if;
            end if;

            -- sampler: slot k at REk + f_ds; it runs on after the last edge for late bits
            if samp_on = '1' then
              if samp_cnt /= 0 then
                samp_cnt <= samp_cnt - 1;
              else
                samp_cnt <= f_p - 1;
                samp_slot <= samp_slot + 1;
                if samp_slot >= f_rel and rx_done = '0' then
                  if rx_data = '0' then
                    -- Polling: the line floats HIGH (fail-safe) until the encoder drives it
                    -- LOW, so the start bit is the first HIGH after a LOW (docs/model.md §1).
                    if seen_low = '0' then
                      if din_s2 = '0' then
                        seen_low <= '1';
                      elsif hi_cnt = 7 then
                        -- Eight HIGH slots and never LOW: type I error handling (D297403 A2)
                        rx_done <= '1';
                        rx_fail <= '1';
                        abort <= '1';
                      else
                        hi_cnt <= hi_cnt + 1;
                      end if;
                    elsif din_s2 = '1' then
                      rx_data <= '1';
                      rx_idx <= to_unsigned(1, 8);
                      -- One more pulse after the last bit (docs/model.md §5)
                      last_re <= samp_slot + resize(f_w, 16);
                    end if;
                  else
                    rx_idx <= rx_next;
                    if rx_next <= f_w - 5 then
                      crc_calc <= (crc_calc(3 downto 0) & '0') xor crc_fb;
                      lsb_sr <= din_s2 & lsb_sr(63 downto 1);
                      msb_sr <= msb_sr(22 downto 0) & din_s2;
                    else
                      crc_rx <= crc_rx(3 downto 0) & din_s2;
                    end if;
                    if rx_next = f_w then
                      rx_done <= '1';
                    end if;
                  end if;
                end if;
              end if;
            end if;

            -- t_D: counter from the RE that carries the start bit to its rising edge (2.1.2)
            if kind = K_MEAS then
              if fe_n >= 9 and din_s2 = '0' then
                meas_low <= '1';
              end if;
              if meas_low = '1' and meas_cap = '0' and din_s2 = '1' and din_prev = '0' then
                meas_cap <= '1';
                meas_val <= tdc;
              end if;
            end if;

            if clk_run = '0' and rx_done = '1' then
              samp_on <= '0';
              st <= ST_EVAL;
            end if;

          -- one frame is over: report it and choose the next
          when ST_EVAL =>
            st <= ST_WAIT;
            gap <= to_unsigned(T_REC, 32);
            use_cycle <= '0';
            case kind is
              when K_MEAS =>
                if crc_ok = '1' and meas_cap = '1' then
                  meas_arr(meas_n) <= meas_val;
                else
                  round_bad <= '1';
                  crc_error <= '1';
                end if;
                if meas_n = N_MEAS - 1 then
                  st <= ST_CALC;
                else
                  meas_n <= meas_n + 1;
                end if;
              when K_POS =>
                if crc_ok = '1' then
                  position <= std_logic_vector(shift_right(unsigned(lsb_sr), 64 - POS_BITS));
                  position_valid <= '1';
                else
                  crc_error <= '1';
                end if;
                pos_n <= pos_n + 1;
                if pos_n + 1 >= N_POS then
                  kind <= K_SEL;
                  gap <= to_unsigned(T_B, 32);
                elsif DEFECT = 2 and crc_ok = '1' then
                  gap <= to_unsigned(T_SHORT, 32);
                else
                  use_cycle <= '1';
                end if;
              when K_SEL =>
                if crc_ok = '1' and msb_sr = x"A10000" then  -- the selection is echoed
                  kind <= K_PAR;
                  gap <= to_unsigned(T_B, 32);
                else
                  crc_error <= '1';
                  st <= ST_DONE;
                end if;
              when K_PAR =>
                if crc_ok = '1' and msb_sr(23 downto 16) = x"0D" then
                  param_value <= msb_sr(15 downto 0);
                  param_valid <= '1';
                else
                  crc_error <= '1';
                end if;
                st <= ST_DONE;
            end case;

          -- N_MEAS values in: accept their mean, or measure again
          when ST_CALC =>
            st <= ST_WAIT;
            meas_n <= 0;
            round_bad <= '0';
            if round_bad = '0' and spread_ok = '1' then
              t_d <= mean;
              t_d_valid <= '1';
              if N_POS = 0 then
                kind <= K_SEL;
                gap <= to_unsigned(T_B, 32);
              else
                kind <= K_POS;
              end if;
            elsif meas_round + 1 < MEAS_ROUNDS then
              meas_round <= meas_round + 1;
            else
              st <= ST_DONE;  -- no trustworthy t_D: no compensated frames
            end if;

          when ST_DONE =>
            done <= '1';
        end case;
      end if;
    end if;
  end process;

end architecture rtl;
