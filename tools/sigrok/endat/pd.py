##
## This file is part of endatsim.
##
## An EnDat 2.2 protocol decoder for libsigrokdecode (api_version 3). Spec references are to
## HEIDENHAIN's EnDat 2.2 specification D297403.
##
## One explicit state machine over CLOCK and DATA at the encoder's connector, the same reading
## as endatsim's checker (checker/frame_decoder.cpp):
##  - a falling CLOCK edge begins a frame (FE1) after CLOCK was HIGH for the encoder's t_m
##    (2.3.2 recovery time I), or after a frame that had every clock it needs when the HIGH
##    phase before it is more than twice the frame's longest;
##  - the master's bits are taken on rising edges (the mode command on RE3..RE8, 2.3; a 2.1
##    payload on the 24 edges after it, 2.4);
##  - the encoder's bit of slot k is taken half-way between RE_k and RE_k+1 plus its
##    CLOCK-to-DATA delay (after the last rising edge, half the last period after it, once CLOCK
##    has been HIGH for t_m, for an answer still short of its bits); the start bit is the first HIGH after a LOW from the turnaround on;
##  - answers are decoded with the layouts of the tables, the CRC as appendix A4 computes it,
##    additional data counted from the command supplements' MRS codes (2.4.2.2) and corrected by
##    the level after each CRC (2.3.5); the supplement's start bit is the first HIGH after a LOW,
##    three clocks after the encoder released DATA.
## Every number it judges with is in tables.py, generated from endatsim's tables.
##

import ctypes

import sigrokdecode as srd

from .tables import TABLES

LIMIT = TABLES['limits']
POSITION = TABLES['frame_position']
DEFAULTS = TABLES['decoder']
CRC = TABLES['crc']
ADDITIONAL = TABLES['additional_data']
STATUS = ADDITIONAL['status']
COMMANDS = {m['bits']: m for m in TABLES['mode_commands']}
CHECKS = {r['check']: r for r in TABLES['checks']}
AREAS = {a['mrs']: a for a in TABLES['memory_areas']}
INFORMATION = {c['code']: c for c in ADDITIONAL['information']}
ERROR_CAUSES = {c['cause']: c for c in TABLES['error_handling']}
PAYLOAD_BITS = TABLES['payload_bits']
DATUM_BITS = ADDITIONAL['datum_bits']
SELECTING_MRS = frozenset(ADDITIONAL['selecting_mrs'])
STOP_MRS = frozenset(ADDITIONAL['stop_mrs'].values())
POSITION_FORMAT = TABLES['position_format']
FUNCTIONS = TABLES['function_initialization']
SECOND_DATUM_FROM = min(c['code'] for c in ADDITIONAL['information'] if c['additional_data'] == 2)
TOLERANCE_PPM = DEFAULTS['f_c_tolerance_ppm']
PS_PER_US = 1000000

# Key of the command that a continuous clock may follow (2.3.1), and of the reset that ends the
# selections of additional data (2.7) and activates a written word 13.
CONTINUOUS = COMMANDS[0b000111]['key']
# The further words of a continuous clock listed with their position and CRC (the rest counted).
WORDS_KEPT = 100


def command_named(key):
    for m in TABLES['mode_commands']:
        if m['key'] == key:
            return m
    raise KeyError(key)


SELECT_AREA = command_named('selection_of_memory_area')['key']
SEND_PARAMETERS = command_named('encoder_send_parameters')['key']
RECEIVE_PARAMETERS = command_named('encoder_receive_parameters')['key']
RESET = command_named('encoder_receive_reset')['key']
SELECT_WITH_POSITION = command_named('encoder_send_position_values_and_selection_of_memory_area')['key']
RECEIVE_WITH_POSITION = command_named('encoder_send_position_values_and_receive_parameter')['key']
SEND_WITH_POSITION = command_named('encoder_send_position_values_and_send_parameter')['key']
# Memory accesses (2.5.1, 2.6.1): no further one while additional data 1 shows Busy.
ACCESSES_21 = frozenset((SELECT_AREA, RECEIVE_PARAMETERS, SEND_PARAMETERS, RESET))


def layout(name, position_bits=None):
    '''[(field, width, lsb_first)] in wire order.'''
    return [(f['field'], f['width'] if f['width'] is not None else position_bits, f['order'] == 'lsb_first')
            for f in TABLES['layouts'][name]]


def layout_width(fields):
    return sum(w for _, w, _ in fields)


def answer_layout(command, position_bits):
    if command['answer'] == 'test_values':
        return layout('test_values')
    if command['answer'] == 'parameter':
        return layout('parameter')
    return layout('position_2_1' if command['version'] == '2.1' else 'position_2_2', position_bits)


def decode_layout(fields, bits):
    '''{field: (value, first bit index, bit count)}.'''
    values, at = {}, 0
    for field, width, lsb_first in fields:
        v = 0
        for i in range(width):
            v |= (bits[at + i] & 1) << (i if lsb_first else width - 1 - i)
        values[field] = (v, at, width)
        at += width
    return values


def crc5(bits):
    '''Appendix A4: the register preset, shifted MSB first, the output inverted.'''
    n = CRC['bits']
    mask = (1 << n) - 1
    reg = CRC['preset'] & mask
    for b in bits:
        feedback = ((reg >> (n - 1)) & 1) ^ (b & 1)
        reg = (reg << 1) & mask
        if feedback:
            reg ^= CRC['polynomial']
    return reg ^ mask if CRC['final_inversion'] else reg


def crc_matches(word):
    '''The CRC over a word's bits between its first bit (start bit or leading LOW) and its CRC.'''
    n = CRC['bits']
    received = 0
    for b in word[-n:]:
        received = received << 1 | b
    return crc5(word[1:-n]) == received


def hx(value, digits):
    return '%0*Xh' % (digits, value)


def fmt_quantity(value, units):
    mag = abs(value)
    scale, name = units[0]
    for s, n in units:
        if mag >= s:
            scale, name = s, n
    text = ('%.6f' % (value / scale)).rstrip('0').rstrip('.')
    return '%s %s' % (text, name)


def fmt_time(ps):
    return fmt_quantity(ps, ((1, 'ps'), (1000, 'ns'), (10**6, 'us'), (10**9, 'ms'), (10**12, 's')))


def fmt_hz(hz):
    return fmt_quantity(hz, ((1, 'Hz'), (1000, 'kHz'), (10**6, 'MHz')))


def data_delay_max(cable_m):
    '''2.3.2 t_D maximum (0.2 + 0.01 x L) us.'''
    return LIMIT['data_delay_base_ps'] + round(cable_m * LIMIT['data_delay_per_metre_ps'])


def start_delay(f_c):
    '''2.3.2 note 8: 2 us up to 8 MHz, 1 us at 16 MHz, linear in between.'''
    lo, hi = LIMIT['fc_max_with_compensation_hz'], LIMIT['fc_max_special_hz']
    over = min(max(f_c - lo, 0), hi - lo)
    span = LIMIT['start_delay_ps'] - LIMIT['start_delay_at_16mhz_ps']
    return LIMIT['start_delay_ps'] - span * over / (hi - lo)


def required_start_delay(f_c, cable_m):
    '''Note 8's value, lengthened with the cable beyond 100 m as t_D's bound grows.'''
    note8 = start_delay(f_c)
    scaled = note8 * data_delay_max(cable_m) / data_delay_max(LIMIT['compensated_cable_max_m'])
    return max(note8, scaled)


def without_glitches(rising, period):
    '''The rising edges without those of glitches, or None when there are none: an edge of the
    clock has a period on each side, a glitch's edge splits one period in two. The edge whose
    neighbours come nearest to one median period apart, within a quarter of it, is dropped, and
    again, until none is that near. Only looked for when a period is shorter than three quarters of
    the fit's.'''
    if len(rising) < 5:
        return None
    periods = [rising[i] - rising[i - 1] for i in range(2, len(rising))]
    if min(periods) * 4 >= 3 * period:
        return None
    median = sorted(periods)[len(periods) // 2]
    kept = list(rising)
    while len(kept) >= 5:
        off, nearest = min((abs(kept[i + 1] - kept[i - 1] - median), i) for i in range(2, len(kept) - 1))
        if off * 4 > median:
            break
        del kept[nearest]
    return kept if len(kept) != len(rising) else None


class Fit:
    '''The frame's clock from a least-squares fit over its rising edges from RE2 on (the first
    period holds t_ST), without the edges of glitches; limits widen by three standard errors of
    the fit.'''

    def __init__(self, rising, ps_per_sample):
        self.fit(rising, ps_per_sample)
        if self.period is not None:
            steady = without_glitches(rising, self.period / ps_per_sample)
            if steady is not None:
                self.fit(steady, ps_per_sample)

    def fit(self, rising, ps_per_sample):
        self.period = None  # ps
        self.uncertainty_ppm = 0
        m = min(len(rising) - 1, DEFAULTS['fit_max_edges'])
        if m < 2:
            return
        ys = [(rising[i + 1] - rising[1]) * ps_per_sample for i in range(m)]
        sx = m * (m - 1) / 2
        sxx = sum(i * i for i in range(m))
        sy = sum(ys)
        sxy = sum(i * y for i, y in enumerate(ys))
        den = m * sxx - sx * sx
        slope = (m * sxy - sx * sy) / den
        if slope <= 0:
            return
        self.period = slope
        if m < 3:
            return
        intercept = (sy - slope * sx) / m
        squares = sum((y - intercept - slope * i) ** 2 for i, y in enumerate(ys))
        if squares > 0:
            sd = (squares / (m - 2) / (den / m)) ** 0.5
            self.uncertainty_ppm = 3 * sd / slope * 1e6

    def hz(self):
        return 1e12 / self.period

    def above(self, bound):
        return self.hz() * 1e6 > bound * (1e6 + TOLERANCE_PPM + self.uncertainty_ppm)

    def below(self, bound):
        return self.hz() * 1e6 < bound * (1e6 - TOLERANCE_PPM - self.uncertainty_ppm)

    def period_below(self, min_ps):
        return self.period * 1e6 < min_ps * (1e6 - TOLERANCE_PPM - self.uncertainty_ppm)


class Frame:
    '''One frame as the wires show it; clocks count rising edges from FE1 (RE1 is the first).'''

    def __init__(self, index, fe1):
        self.index = index
        self.fe1 = fe1
        self.rising = []
        self.falling = [fe1]
        self.longest_high = 0
        self.mode_bits = 0
        self.mode_bits_seen = 0
        self.command = None
        self.payload = None
        self.start_bit_clock = 0
        self.answer_bits = 0
        self.answer_complete = False
        self.fields = {}
        self.crc_ok = False
        self.additional_data = []  # (status, data, crc_ok, first bit index)
        self.supplement = None
        self.supplement_last_clock = 0
        self.continuous_words = 0
        self.words = []  # (position, crc_ok) of the first WORDS_KEPT further words, as endatsim check keeps them
        self.bad_words = 0
        self.complete = False
        self.learnt_position_bits = 0
        self.answer_shown = False
        self.low_runs = []  # (clock, LOW bits) before each later word of a continuous clock
        self.low_at_last_rise = False
        self.release = None  # the encoder's driver off: (sample, falling edges seen)
        self.drive = None    # and on again
        self.between_judged = False

    @property
    def clocks(self):
        return len(self.rising)


# Annotation classes.
(A_MASTER_BIT, A_ENCODER_BIT, A_COMMAND, A_NO_COMMAND, A_MODE_BITS, A_ADDRESS, A_PARAMETER, A_START,
 A_F1, A_F2, A_POSITION, A_TEST_VALUE, A_CRC_OK, A_CRC_BAD, A_DATUM, A_STATUS, A_DATUM_DATA,
 A_SUPPLEMENT, A_FRAME, A_CLOCK, A_TIMING, A_DRIVER, A_VIOLATION, A_WARNING, A_UNDECIDED) = range(25)

# Sample queue entries: (due, clock, master).
HEADER, PAYLOAD, HUNT, ANSWER, MORE_DATA, SUPPLEMENT_HUNT, SUPPLEMENT, DONE = range(8)

AT_REST = 'at rest if CLOCK is HIGH'
INSIDE = 'inside a frame'


class SamplerateError(Exception):
    pass


class Decoder(srd.Decoder):
    api_version = 3
    id = 'endat'
    name = 'EnDat'
    longname = 'EnDat 2.2 (HEIDENHAIN encoder interface)'
    desc = 'Bidirectional synchronous serial position-encoder interface (EnDat 2.1 and 2.2).'
    license = 'apache2'
    inputs = ['logic']
    outputs = []
    tags = ['Embedded/industrial']
    channels = (
        {'id': 'clk', 'name': 'CLOCK', 'desc': 'CLOCK at the encoder connector'},
        {'id': 'data', 'name': 'DATA', 'desc': 'DATA at the encoder connector'},
    )
    optional_channels = (
        {'id': 'de', 'name': 'DE', 'desc': "Encoder's DATA driver enable"},
    )
    options = (
        {'id': 'position_bits', 'desc': 'Position bits (until word 13 is read)',
         'default': DEFAULTS['position_bits']},
        {'id': 'clock_to_data_ns', 'desc': 'Encoder CLOCK-to-DATA delay (ns)',
         'default': DEFAULTS['clock_to_data_ps'] / 1000.0},
        {'id': 't_m_us', 'desc': 'Encoder recovery time t_m (us)', 'default': DEFAULTS['t_m_ps'] / 1e6},
        {'id': 't_m_short_us', 'desc': 'Encoder short t_m when word 3 selects it (us, 0: none)', 'default': 0.0},
        {'id': 'short_t_m', 'desc': 'Word 3 selects the short t_m at the start', 'default': 'no',
         'values': ('no', 'yes')},
        {'id': 't_r_ns', 'desc': 'Encoder recovery time t_R (ns)', 'default': LIMIT['recovery_time_2_min_ps'] / 1000.0},
        {'id': 'cable_m', 'desc': 'Cable length (m)', 'default': 0.0},
        {'id': 'start', 'desc': 'Capture begins', 'default': AT_REST, 'values': (AT_REST, INSIDE)},
        {'id': 'de_polarity', 'desc': 'DE active level', 'default': 'high', 'values': ('high', 'low')},
    )
    annotations = (
        ('master-bit', 'Master bit'),
        ('encoder-bit', 'Encoder bit'),
        ('command', 'Mode command'),
        ('no-command', 'Mode bits without a command'),
        ('mode-bits', 'Mode bits'),
        ('address', 'Address / MRS code'),
        ('parameter', 'Parameter'),
        ('start-bit', 'Start bit'),
        ('f1', 'F1 (error 1)'),
        ('f2', 'F2 (error 2)'),
        ('position', 'Position'),
        ('test-value', 'Test value'),
        ('crc-ok', 'CRC ok'),
        ('crc-bad', 'CRC error'),
        ('datum-low', 'Additional datum start (LOW)'),
        ('datum-status', 'Additional data status'),
        ('datum-data', 'Additional data'),
        ('supplement', 'Command supplement'),
        ('frame', 'Frame'),
        ('clock', 'Clock timing'),
        ('timing', 'Answer timing'),
        ('driver', 'Driver timing'),
        ('violation', 'Violation'),
        ('warning', 'Warning'),
        ('undecided', 'Undecided at this resolution'),
    )
    annotation_rows = (
        ('bits', 'Bits', (A_MASTER_BIT, A_ENCODER_BIT)),
        ('commands', 'Mode commands', (A_COMMAND, A_NO_COMMAND)),
        ('fields', 'Fields', (A_MODE_BITS, A_ADDRESS, A_PARAMETER, A_START, A_F1, A_F2, A_POSITION,
                              A_TEST_VALUE, A_CRC_OK, A_CRC_BAD, A_DATUM, A_STATUS, A_DATUM_DATA,
                              A_SUPPLEMENT)),
        ('frames', 'Frames', (A_FRAME,)),
        ('clock-timing', 'Clock timing', (A_CLOCK,)),
        ('answer-timing', 'Answer timing', (A_TIMING,)),
        ('driver-timing', 'Driver timing', (A_DRIVER,)),
        ('violations', 'Timing rows', (A_VIOLATION, A_WARNING, A_UNDECIDED)),
    )

    def __init__(self):
        self.reset()

    def reset(self):
        self.samplerate = None
        self.frame = None
        self.frames = 0
        self.pending = []      # encoder and master bits still to take: (due, clock, master)
        self.changes = []      # DATA changes still needed for sampling: (sample, level)
        self.tail = None       # the slot after the last rising edge, read there if no edge follows
        self.base_level = 1    # DATA before the first of them
        self.data_level = 1
        self.clock_level = 1
        self.last_rise = 0
        self.at_rest = True
        self.state = DONE
        self.bits = []         # the answer's bits and their slots
        self.slots = []
        self.shift = 0
        self.shifted = 0
        self.shift_from = 0
        self.seen_low = False
        self.low_run = 0
        self.release_clock = 0
        self.layout = []
        self.selected = [False, False]
        self.area = None
        self.written_width = None
        self.previous_end = None  # (last rising edge, version, error handling) of the frame before
        self.measurement_seen = False
        self.written_word3 = None  # word 3 as written, until a reset activates it (3.4.4)
        self.busy_since = None     # the end of the last 2.2 memory access, until Busy = 0
        self.busy_reported = False
        self.awaiting_not_busy = None  # the frame of that access
        self.awaiting_known = False

    def metadata(self, key, value):
        if key == srd.SRD_CONF_SAMPLERATE:
            self.samplerate = value

    def start(self):
        self.out_ann = self.register(srd.OUTPUT_ANN)
        self.position_bits = int(self.options['position_bits'])
        self.cable_m = float(self.options['cable_m'])
        self.de_active = 1 if self.options['de_polarity'] == 'high' else 0
        self.short_t_m = self.options['short_t_m'] == 'yes'

    # ---- time ----------------------------------------------------------------------------------

    def ps(self, samples):
        return samples * self.ps_per_sample

    def samples(self, ps):
        return ps / self.ps_per_sample

    def judge_at_least(self, measured, bound):
        '''measured >= bound (ps), undecided within one sample either way.'''
        r = self.ps_per_sample
        if measured - r >= bound:
            return 'pass'
        if measured + r <= bound:
            return 'fail'
        return 'undecided'

    def judge_at_most(self, measured, bound):
        r = self.ps_per_sample
        if measured + r <= bound:
            return 'pass'
        if measured - r >= bound:
            return 'fail'
        return 'undecided'

    def judge_more_than(self, measured, bound):
        decision = self.judge_at_least(measured, bound)
        return 'undecided' if decision == 'pass' and measured - self.ps_per_sample <= bound else decision

    # ---- output --------------------------------------------------------------------------------

    def put_ann(self, ss, es, cls, texts):
        ss = int(round(ss))
        es = max(ss, int(round(es)))
        self.put(ss, es, self.out_ann, [cls, texts])

    def finding(self, ss, es, decision, check, measured, bound, message, severity='error'):
        '''A timing row's finding: a violation, a warning or undecided at the resolution.'''
        if decision == 'pass':
            return
        row = CHECKS[check]
        cls = A_UNDECIDED if decision == 'undecided' else A_VIOLATION if severity == 'error' else A_WARNING
        verdict = 'undecided: ' if decision == 'undecided' else 'warning: ' if severity != 'error' else ''
        long = '%s%s %s, limit %s: %s [%s]' % (verdict, check, measured, bound, message, row['section'])
        self.put_ann(ss, es, cls, [long, '%s%s %s (%s)' % (verdict, check, measured, bound), check])

    # ---- bits ----------------------------------------------------------------------------------

    def master_span(self, clock):
        '''The master's bit taken on RE_clock: from FE_clock, as long again after RE_clock.'''
        f = self.frame
        rise = f.rising[clock - 1]
        fall = f.falling[clock - 1] if clock <= len(f.falling) else rise
        return fall, rise + (rise - fall)

    def encoder_span(self, slot):
        '''The encoder's bit of slot k: from RE_k to RE_k+1, plus its CLOCK-to-DATA delay.'''
        f = self.frame
        ss = f.rising[slot - 1] + self.ctd
        es = f.rising[slot] + self.ctd if slot < len(f.rising) else ss
        return ss, es

    def insert(self, sample):
        at = len(self.pending)
        while at > 0 and self.pending[at - 1][0] > sample[0]:
            at -= 1
        self.pending.insert(at, sample)

    def level_at(self, t):
        level = self.base_level
        for when, value in self.changes:
            if when > t:
                break
            level = value
        return level

    def resolve(self, t):
        while self.pending and self.pending[0][0] < t:
            due, clock, master = self.pending.pop(0)
            bit = self.level_at(due)
            if self.frame is None:
                continue
            if master:
                self.on_master_bit(clock, bit)
            else:
                self.on_encoder_bit(clock, bit)
        # CLOCK stayed HIGH after the last rising edge long enough to end the frame: the slot after
        # it had no edge to read it, and an answer still short of its bits takes it there (a master
        # that gives no pulse after the last bit samples it so).
        high = t - self.last_rise
        if (self.tail is not None and self.frame is not None and self.state == ANSWER and self.clock_level
                and (high >= self.t_m or (self.frame.complete and high > 2 * self.frame.longest_high))
                and self.tail[0] < t):
            due, clock, master = self.tail
            self.tail = None
            self.on_encoder_bit(clock, self.level_at(due))
        # Changes before the earliest sample still due are folded into the level they left; in
        # a frame, changes after its last rising edge stay until the next one.
        horizon = self.pending[0][0] if self.pending and self.pending[0][0] < t else t
        if self.frame is not None and t - self.last_rise < self.t_m:
            horizon = min(horizon, self.last_rise)
        while self.changes and self.changes[0][0] <= horizon:
            self.base_level = self.changes.pop(0)[1]

    # ---- CLOCK and DATA ------------------------------------------------------------------------

    def on_data(self, t, level):
        self.resolve(t)
        if level == self.data_level:
            return
        self.data_level = level
        self.changes.append((t, level))

    def on_driver(self, t, enabled):
        f = self.frame
        if f is None:
            return
        if not enabled and f.release is None:
            f.release = (t, len(f.falling))
        elif enabled and f.release is not None and f.drive is None:
            f.drive = (t, len(f.falling))

    def on_clock(self, t, level):
        self.resolve(t)
        if level == self.clock_level:
            return
        self.clock_level = level
        self.tail = None
        if level:
            self.last_rise = t
            if self.frame is not None:
                self.on_rising(t)
            return
        high = t - self.last_rise
        if not self.at_rest:
            if high < self.t_m:
                return
            self.at_rest = True
        f = self.frame
        if f is None or high >= self.t_m or (f.complete and high > 2 * f.longest_high):
            if f is not None:
                self.end_frame()
            self.begin_frame(t)
            return
        f.longest_high = max(f.longest_high, high)
        f.falling.append(t)

    def on_rising(self, t):
        f = self.frame
        f.rising.append(t)
        f.low_at_last_rise = self.data_level == 0
        k = len(f.rising)
        self.insert((t, k, True))
        if k >= 2:
            r = f.rising[k - 2]
            self.insert((r + (t - r) / 2 + self.ctd, k - 1, False))
            self.tail = (t + (t - r) / 2 + self.ctd, k, False)

    def frame_over(self, t):
        '''CLOCK has stayed HIGH long enough that the next falling edge begins a frame.'''
        f = self.frame
        if f is None or self.clock_level == 0 or not f.rising:
            return False
        high = t - self.last_rise
        return high >= self.t_m or (f.complete and high > 2 * f.longest_high)

    def timeout(self):
        '''The sample at which the current frame is over if CLOCK stays HIGH.'''
        f = self.frame
        if f is None or self.clock_level == 0 or not f.rising:
            return None
        at = self.last_rise + self.t_m
        if f.complete:
            at = min(at, self.last_rise + 2 * f.longest_high + 1)
        if self.pending:
            at = max(at, self.pending[-1][0] + 1)
        if self.tail is not None and self.state == ANSWER:
            at = max(at, self.tail[0] + 1)
        return at

    # ---- frames --------------------------------------------------------------------------------

    def begin_frame(self, t):
        self.frame = Frame(self.frames, t)
        self.frames += 1
        self.state = HEADER
        self.shift = 0
        self.shifted = 0
        self.seen_low = False
        self.bits = []
        self.slots = []
        self.tail = None

    def end_frame(self):
        f = self.frame
        if f.command is not None and f.command['key'] == RESET:
            self.selected = [False, False]  # 2.7: a reset ends every selection of additional data
        self.follow_parameter_reads()
        if not f.answer_shown and f.answer_complete:
            self.show_answer()
        elif not f.answer_complete and self.state == ANSWER:
            for slot, bit in zip(self.slots, self.bits):  # an answer the clock stopped inside
                self.put_bit(slot, bit, False)
        if not f.between_judged:
            self.judge_between_frames()
        text = frame_text(f)
        es = f.rising[-1] if f.rising else f.fe1
        self.put_ann(f.fe1, es, A_FRAME, ['#%d %s' % (f.index, text), text])
        self.evaluate(f)
        if f.command is not None:
            self.judge_busy(f)
            if f.answer_complete and f.crc_ok:
                self.follow_settings(f)
        self.frame = None
        self.state = DONE

    # ---- the master's bits ---------------------------------------------------------------------

    def on_master_bit(self, clock, bit):
        f = self.frame
        s = self.state
        if s == HEADER:
            if clock < POSITION['first_mode_bit'] or clock > POSITION['last_mode_bit']:
                return
            self.put_bit(clock, bit, True)
            f.mode_bits = (f.mode_bits << 1) | bit
            f.mode_bits_seen += 1
            if f.mode_bits_seen == POSITION['mode_bits']:
                self.decode_mode_command()
        elif s == PAYLOAD:
            self.put_bit(clock, bit, True)
            self.shift_in(clock, bit)
            if self.shifted == PAYLOAD_BITS:
                f.payload = self.shift
                self.show_master_word(self.shift_from, clock, f.payload, 'payload')
                self.state = HUNT
        elif s == SUPPLEMENT_HUNT:
            # The line floats until the master drives its lead bits; the supplement's start bit
            # is the first HIGH after a LOW.
            if clock <= self.release_clock + DEFAULTS['supplement_ignore_clocks']:
                return
            if not self.seen_low:
                self.seen_low = not bit
            elif bit:
                self.state = SUPPLEMENT
                self.shift = 0
                self.shifted = 0
                ss, es = self.master_span(clock)
                self.put_bit(clock, bit, True)
                self.put_ann(ss, es, A_SUPPLEMENT, ['Supplement start bit', 'S', 'S'])
        elif s == SUPPLEMENT:
            self.put_bit(clock, bit, True)
            self.shift_in(clock, bit)
            if self.shifted == PAYLOAD_BITS:
                f.supplement = self.shift
                f.supplement_last_clock = clock
                self.show_master_word(self.shift_from, clock, f.supplement, 'supplement')
                self.note_selection()
                f.complete = True
                self.state = DONE

    def shift_in(self, clock, bit):
        if self.shifted == 0:
            self.shift_from = clock
        self.shift = (self.shift << 1) | bit
        self.shifted += 1

    def decode_mode_command(self):
        f = self.frame
        f.command = COMMANDS.get(f.mode_bits)
        first, last = POSITION['first_mode_bit'], POSITION['last_mode_bit']
        ss, es = self.master_span(first)[0], self.master_span(last)[1]
        bits = format(f.mode_bits, '06b')
        self.put_ann(ss, es, A_MODE_BITS, ['Mode bits ' + bits, bits])
        if f.command is None:  # A2 type I: the encoder answers no start bit
            cause = ERROR_CAUSES[1]  # A2: the mode command disrupted or not supported
            self.put_ann(ss, es, A_NO_COMMAND, ['Mode bits %s: no mode command (type %s, A2: %s)' % (
                bits, 'I' * cause['type'], cause['text']), 'No mode command', '?'])
            self.state = DONE
        else:
            c = f.command
            self.put_ann(ss, es, A_COMMAND, ['%s (EnDat %s, %s)' % (c['name'], c['version'], bits), c['name'],
                                             c['key'], bits])
            self.layout = answer_layout(c, self.position_bits)
            extra = DATUM_BITS * self.expected_additional_data() if self.carries_additional_data() else 0
            f.answer_bits = layout_width(self.layout) + extra
            self.shift = 0
            self.shifted = 0
            self.seen_low = False
            self.state = PAYLOAD if c['payload_bits'] else HUNT
        self.judge_between_frames()

    def carries_additional_data(self):
        c = self.frame.command
        return c['answer'] == 'position' and c['version'] == '2.2'

    def expected_additional_data(self):
        return int(self.selected[0]) + int(self.selected[1])

    def note_selection(self):
        '''2.4.2.2: MRS codes 40h + I select additional data 1, 50h + (I - 16) additional data 2;
        4Fh and 5Fh stop sending it.'''
        f = self.frame
        if f.command['key'] != SELECT_WITH_POSITION:
            return
        mrs = f.supplement >> 16
        if mrs not in SELECTING_MRS:
            return
        which = 1 if INFORMATION[mrs & STATUS['information']]['additional_data'] == 2 else 0
        self.selected[which] = mrs not in STOP_MRS

    # ---- the encoder's bits --------------------------------------------------------------------

    def on_encoder_bit(self, clock, bit):
        f = self.frame
        s = self.state
        if s == HUNT:
            payload = f.command['payload_bits'] if f.command else 0
            if clock < POSITION['turnaround'] + payload:
                return
            if not self.seen_low:
                self.seen_low = not bit
                self.low_run = 1 if self.seen_low else 0
                return
            if not bit:
                self.low_run += 1
                return
            if f.continuous_words == 0 and f.start_bit_clock == 0:
                f.start_bit_clock = clock
            elif f.answer_complete:
                f.low_runs.append((clock, self.low_run))
            self.bits = [1]
            self.slots = [clock]
            self.state = ANSWER
        elif s == ANSWER:
            # 2.3.5: each additional datum opens with a LOW bit; a HIGH there (the level after the
            # CRC) says no further datum follows.
            width = layout_width(self.layout)
            n = len(self.bits)
            if not f.answer_complete and n >= width and (n - width) % DATUM_BITS == 0 and bit:
                f.answer_bits = n
                self.decode_answer(clock - 1)
                return
            self.bits.append(bit)
            self.slots.append(clock)
            if len(self.bits) == (width if f.answer_complete else f.answer_bits):
                self.decode_answer(clock)
        elif s == MORE_DATA:
            # After the data expected, a LOW opens a datum not known to be selected.
            self.state = DONE
            if bit:
                self.show_answer()
                return
            self.bits.append(0)
            self.slots.append(clock)
            f.answer_bits += DATUM_BITS
            f.answer_complete = False
            f.complete = False
            f.additional_data = []
            self.state = ANSWER

    def decode_answer(self, last_clock):
        f = self.frame
        width = layout_width(self.layout)
        if f.answer_complete:  # a further word of a continuous clock
            f.continuous_words += 1
            crc_ok = crc_matches(self.bits[:width])
            f.bad_words += 0 if crc_ok else 1
            if len(f.words) < WORDS_KEPT:
                f.words.append((decode_layout(self.layout, self.bits[:width])['position'][0], crc_ok))
            self.show_word(self.layout, self.bits[:width], self.slots[:width], f.continuous_words)
            self.seen_low = False
            self.state = HUNT
            return
        f.answer_complete = True
        f.fields = decode_layout(self.layout, self.bits)
        f.crc_ok = crc_matches(self.bits[:width])
        at = width
        while at + DATUM_BITS <= len(self.bits):
            word = self.bits[at:at + DATUM_BITS]
            v = decode_layout(layout('additional_datum'), word)
            f.additional_data.append((v['status'][0], v['additional_data'][0], word[0] == 0 and crc_matches(word), at))
            at += DATUM_BITS
        if self.carries_additional_data():  # what the encoder sent tells what is selected
            self.selected = [False, False]
            for status, _, _, _ in f.additional_data:
                self.selected[1 if (status & STATUS['information']) >= SECOND_DATUM_FROM else 0] = True
        if f.command['supplement']:
            # The encoder releases DATA on the rising edge after its last bit's slot.
            self.release_clock = last_clock + 1
            self.seen_low = False
            self.show_answer()
            self.state = SUPPLEMENT_HUNT
            return
        f.complete = True
        self.seen_low = False
        if f.command['key'] == CONTINUOUS:
            self.show_answer()
            self.state = HUNT
        elif self.carries_additional_data() and len(f.additional_data) < 2:
            self.state = MORE_DATA
        else:
            self.show_answer()
            self.state = DONE

    def follow_parameter_reads(self):
        '''3.5.6: word 13 of the encoder manufacturer's parameters (area A1h) gives the position's
        clock pulses; a read of it, or an echoed write activated by the next reset, sets the width
        of every later answer.'''
        f = self.frame
        if f.command is None or not f.answer_complete or not f.crc_ok:
            return
        key = f.command['key']
        if key == SELECT_AREA and f.payload is not None:
            self.area = f.payload >> 16
        elif key == SELECT_WITH_POSITION and f.supplement is not None and (f.supplement >> 16) not in SELECTING_MRS:
            self.area = f.supplement >> 16
        elif key == SEND_PARAMETERS:
            bits = self.position_format_word(f)
            if bits:
                self.learn_width(bits)
        elif key == RECEIVE_PARAMETERS:
            echo = (f.fields['address'][0] << 16) | f.fields['parameter'][0]
            bits = self.position_format_word(f)
            if bits and echo == f.payload:
                self.written_width = bits
        elif key == RESET:
            if self.written_width:
                self.learn_width(self.written_width)
            self.written_width = None

    def follow_settings(self, f):
        '''3.4.4: word 3 of the operating status (area B9h), written by a 2.1 or a 2.2 command, is
        activated by the next "Encoder receive reset"; it selects the short recovery time I for
        2.2 mode commands or the normal one.'''
        key = f.command['key']
        write = f.payload if key == RECEIVE_PARAMETERS else f.supplement if key == RECEIVE_WITH_POSITION else None
        if write is not None and self.area == FUNCTIONS['area_mrs'] and (write >> 16) == FUNCTIONS['word']:
            self.written_word3 = write & 0xFFFF
        elif key == RESET:
            if self.written_word3 is not None:
                mask = FUNCTIONS['short_recovery_time_mask']
                self.short_t_m = (self.written_word3 & mask) == FUNCTIONS['short_recovery_time_activated']
            self.written_word3 = None

    def position_format_word(self, f):
        if self.area != POSITION_FORMAT['area_mrs'] or f.payload is None or (f.payload >> 16) != POSITION_FORMAT['word']:
            return 0
        word = f.payload & 0xFFFF if f.command['key'] == RECEIVE_PARAMETERS else f.fields['parameter'][0]
        return word & POSITION_FORMAT['bits_mask']

    def learn_width(self, bits):
        self.position_bits = bits
        self.frame.learnt_position_bits = bits

    # ---- annotations of fields -----------------------------------------------------------------

    def put_bit(self, clock, bit, master):
        if master:
            ss, es = self.master_span(clock)
            self.put_ann(ss, es, A_MASTER_BIT, [str(bit)])
        else:
            ss, es = self.encoder_span(clock)
            self.put_ann(ss, es, A_ENCODER_BIT, [str(bit)])

    def show_master_word(self, first, last, value, what):
        '''The master's 8 + 16 bits: a 2.1 payload or a 2.2 command supplement (MSB first).'''
        address, parameter = value >> 16, value & 0xFFFF
        split = first + 8
        a_ss, a_es = self.master_span(first)[0], self.master_span(split - 1)[1]
        p_ss, p_es = self.master_span(split)[0], self.master_span(last)[1]
        label = 'Supplement ' if what == 'supplement' else ''
        self.put_ann(a_ss, a_es, A_ADDRESS, [label + address_text(self.frame.command, address, what), label +
                                             hx(address, 2), hx(address, 2)])
        self.put_ann(p_ss, p_es, A_PARAMETER, ['%sParameter %s' % (label, hx(parameter, 4)), hx(parameter, 4)])

    def slot_span(self, slots, first, count):
        return self.encoder_span(slots[first])[0], self.encoder_span(slots[first + count - 1])[1]

    def show_answer(self):
        f = self.frame
        if f.answer_shown:
            return
        f.answer_shown = True
        for i in range(min(len(self.bits), f.answer_bits)):
            self.put_bit(self.slots[i], self.bits[i], False)
        self.show_fields(f.fields, self.slots, f.crc_ok, '')
        for status, data, crc_ok, at in f.additional_data:
            self.show_datum(status, data, crc_ok, at)

    def show_word(self, fields_layout, bits, slots, word):
        for i, b in enumerate(bits):
            self.put_bit(slots[i], b, False)
        self.show_fields(decode_layout(fields_layout, bits), slots, crc_matches(bits), 'Word %d: ' % word)

    def show_fields(self, fields, slots, crc_ok, prefix):
        for field, (value, at, width) in fields.items():
            ss, es = self.slot_span(slots, at, width)
            if field == 'start_bit':
                self.put_ann(ss, es, A_START, [prefix + 'Start bit', 'S'])
            elif field == 'f1':
                self.put_ann(ss, es, A_F1, ['%sF1 %d%s' % (prefix, value, ' (error)' if value else ''), 'F1 %d' % value])
            elif field == 'f2':
                self.put_ann(ss, es, A_F2, ['%sF2 %d%s' % (prefix, value, ' (error, low-active)' if not value else ''),
                                            'F2 %d' % value])
            elif field == 'position':
                self.put_ann(ss, es, A_POSITION, ['%sPosition %d (%d bits)' % (prefix, value, width),
                                                  'Position %d' % value, str(value)])
            elif field == 'test_value':
                self.put_ann(ss, es, A_TEST_VALUE, [prefix + 'Test value ' + hx(value, 10), hx(value, 10)])
            elif field == 'address':
                refused = ' (inverted: the access refused, type II)' if refused_access(self.frame) else ''
                self.put_ann(ss, es, A_ADDRESS, [prefix + 'Echo address ' + hx(value, 2) + refused, hx(value, 2)])
            elif field == 'parameter':
                self.put_ann(ss, es, A_PARAMETER, [prefix + 'Echo parameter ' + hx(value, 4), hx(value, 4)])
            elif field == 'crc':
                cls = A_CRC_OK if crc_ok else A_CRC_BAD
                verdict = 'ok' if crc_ok else 'BAD'
                self.put_ann(ss, es, cls, ['%sCRC %02d %s' % (prefix, value, verdict), 'CRC ' + verdict, verdict])

    def show_datum(self, status, data, crc_ok, at):
        code = status & STATUS['information']
        info = INFORMATION[code]
        which = info['additional_data']
        flags = [name for name, key in (('WRN', 'warning'), ('RM', 'reference_mark'), ('Busy', 'busy'))
                 if status & STATUS[key]]
        fields = decode_layout(layout('additional_datum'), [0] * DATUM_BITS)
        slots = self.slots[at:at + DATUM_BITS]
        for field, (_, first, width) in fields.items():
            ss, es = self.slot_span(slots, first, width)
            if field == 'leading_low':
                self.put_ann(ss, es, A_DATUM, ['Additional data %d' % which, 'AD%d' % which])
            elif field == 'status':
                text = 'AD%d status %s: I=%d %s' % (which, hx(status, 2), code, info['name'])
                self.put_ann(ss, es, A_STATUS, [text + (', ' + ' '.join(flags) if flags else ''),
                                                'AD%d I=%d%s' % (which, code, ' ' + ' '.join(flags) if flags else ''),
                                                'I=%d' % code])
            elif field == 'additional_data':
                self.put_ann(ss, es, A_DATUM_DATA, ['AD%d data %s (%s)' % (which, hx(data, 4), info['key']),
                                                    'AD%d %s' % (which, hx(data, 4)), hx(data, 4)])
            elif field == 'crc':
                cls = A_CRC_OK if crc_ok else A_CRC_BAD
                verdict = 'ok' if crc_ok else 'BAD'
                self.put_ann(ss, es, cls, ['AD%d CRC %s' % (which, verdict), 'CRC ' + verdict, verdict])

    # ---- timing rows ---------------------------------------------------------------------------

    def judge_between_frames(self):
        '''Once the frame's mode command is known (t_b depends on it): recovery time I and II
        (t_m, t_R), the wait after an error handling (A2) and t_b (2.3.2).'''
        f = self.frame
        f.between_judged = True
        prev = self.previous_end
        if prev is None:
            return
        last_rise, version, error_handling = prev
        gap = self.ps(f.fe1 - last_rise)
        self.put_ann(last_rise, f.fe1, A_CLOCK, ['Recovery %s (last RE to FE1)' % fmt_time(gap), fmt_time(gap)])
        if error_handling:
            bound = LIMIT['error_recovery_wait_ps']
            self.finding(last_rise, f.fe1, self.judge_at_least(gap, bound), 'error_recovery', fmt_time(gap),
                         '>= ' + fmt_time(bound), 'the next frame followed an error handling too soon')
        c = f.command
        if c is not None and c['version'] == '2.1' and c['payload_bits']:
            bound = LIMIT['time_between_cycles_min_ps']
            self.finding(last_rise, f.fe1, self.judge_more_than(gap, bound), 't_b', fmt_time(gap),
                         '> ' + fmt_time(bound), 'a 2.1 memory or parameter frame followed the previous frame too soon')
        short = version == '2.2' and self.short_t_m
        t_m = self.t_m_short_ps if short and self.t_m_short_ps else self.t_m_ps
        declared = t_m + self.t_r_ps
        envelope = (LIMIT['short_recovery_time_max_ps'] if short else LIMIT['recovery_time_max_ps']) + \
            LIMIT['recovery_time_2_min_ps']
        to_encoder = self.judge_at_least(gap, declared)
        if to_encoder != 'pass':
            self.finding(last_rise, f.fe1, to_encoder, 't_m_t_r', fmt_time(gap), '>= t_m + t_R = ' + fmt_time(declared),
                         'the next frame began before the encoder\'s recovery time had elapsed')
        else:
            self.finding(last_rise, f.fe1, self.judge_at_least(gap, envelope), 't_m_t_r', fmt_time(gap),
                         '>= ' + fmt_time(envelope) + ' (spec envelope)',
                         'suits this encoder, but any compliant encoder may need t_m %s + t_R'
                         % fmt_time(envelope - LIMIT['recovery_time_2_min_ps']), severity='warning')

    def evaluate(self, f):
        '''The rows of a frame, at its end: f_c, t_HI, t_LO, the on-off ratio, t_ST, t_cal, t_ac,
        the number of clock pulses, and with the driver enable t_z and t_OE.'''
        rising = f.rising
        c = f.command
        self.previous_end = (rising[-1], c['version'] if c else None, f.start_bit_clock == 0) if rising else \
            self.previous_end
        if not rising:
            return
        fit = Fit(rising, self.ps_per_sample)
        f_c = None
        compensated = False
        if fit.period is not None:
            f_c = fit.hz()
            compensated = fit.above(LIMIT['fc_max_without_compensation_hz'])
        elif len(rising) == 2 and rising[1] > rising[0]:
            f_c = 1e12 / self.ps(rising[1] - rising[0])
            compensated = f_c > LIMIT['fc_max_without_compensation_hz']
        period = 1e12 / f_c if f_c else None
        self.judge_pulse_widths(f, compensated)
        self.judge_on_off_ratio(f, compensated, period)
        if fit.period is not None:
            self.judge_frequency(f, fit, compensated)
        self.judge_start_delay(f, compensated, f_c)
        self.judge_answer_timing(f, period)
        self.judge_clock_count(f)
        if self.has_de:
            self.judge_driver(f, period)

    def phases(self, f):
        '''(HIGH?, k, start, width in ps): LOW k from FE_k to RE_k, HIGH k from RE_k to FE_k+1.'''
        for k in range(min(len(f.rising), len(f.falling))):
            yield False, k + 1, f.falling[k], self.ps(f.rising[k] - f.falling[k])
        for k in range(min(len(f.falling) - 1, len(f.rising))):
            yield True, k + 1, f.rising[k], self.ps(f.falling[k + 1] - f.rising[k])

    def worst(self, found, shorter_is_worse):
        '''The worst failed phase, else the worst undecided one: (decision, high, k, start, width).'''
        for decision in ('fail', 'undecided'):
            cases = [x for x in found if x[0] == decision]
            if cases:
                return (min if shorter_is_worse else max)(cases, key=lambda x: x[4])
        return None

    def show_phase(self, worst, check, bound, message):
        if worst is None:
            return
        decision, high, k, start, width = worst
        end = start + self.samples(width)
        self.finding(start, end, decision, check, '%s %d %s' % ('HIGH' if high else 'LOW', k, fmt_time(width)), bound,
                     message)

    def judge_pulse_widths(self, f, compensated):
        '''2.3.2 t_HI and t_LO: 0.2 us minimum without delay compensation (with it the on-off
        ratio row bounds them), t_HI at most 10 us.'''
        minimum, high_max = LIMIT['pulse_width_min_ps'], LIMIT['pulse_high_max_ps']
        short_low, short_high, long_high = [], [], []
        for high, k, start, width in self.phases(f):
            if not compensated:
                (short_high if high else short_low).append((self.judge_at_least(width, minimum), high, k, start, width))
            if high:
                long_high.append((self.judge_at_most(width, high_max), high, k, start, width))
        self.show_phase(self.worst(short_low, True), 't_lo', '>= ' + fmt_time(minimum), 'CLOCK LOW phase too short')
        self.show_phase(self.worst(short_high, True), 't_hi', '>= ' + fmt_time(minimum), 'CLOCK HIGH phase too short')
        self.show_phase(self.worst(long_high, False), 't_hi', '<= ' + fmt_time(high_max),
                        'CLOCK HIGH phase inside a frame too long: the encoder may end the transfer (t_m)')

    def judge_on_off_ratio(self, f, compensated, period):
        '''With compensation each phase (after t_ST) at least 50 % - 10 % of T; without, where the
        cable and not the 2 MHz bounds f_c, the shorter phase at least t_D max for the cable.'''
        if len(f.rising) < 2 or period is None:
            return
        if compensated:
            minimum = period * (50 - LIMIT['on_off_ratio_error_percent']) / 100
            bound = '>= %s (40 %% of T = %s)' % (fmt_time(minimum), fmt_time(period))
        else:
            if self.measurement_seen:
                return
            t_d = data_delay_max(self.cable_m)
            if 2 * t_d <= 1e12 / LIMIT['fc_max_without_compensation_hz'] or period < 2 * t_d:
                return
            minimum = t_d
            bound = '>= t_D max %s for the cable' % fmt_time(t_d)
        found = [(self.judge_at_least(width, minimum), high, k, start, width) for high, k, start, width in self.phases(f)
                 if high or k > 1 or not compensated]
        self.show_phase(self.worst(found, True), 'on_off_ratio', bound, 'CLOCK phase too short for the period')

    def judge_frequency(self, f, fit, compensated):
        '''2.3.2 f_c: 100 kHz .. 2 MHz without, .. 8 MHz with delay compensation (16 MHz for special
        applications); without compensation also 1 / (2 t_D max) for the cable (2.3.2 note 4 and 2.1.1).'''
        f_c = fit.hz()
        ss, es = f.rising[1], f.rising[-1]
        c = f.command
        self.put_ann(f.rising[0], es, A_CLOCK, ['f_c %s (%s delay compensation)' % (fmt_hz(f_c), 'with' if compensated
                                                                                   else 'without'), fmt_hz(f_c)])
        if c is not None and c['key'] == CONTINUOUS and f_c <= LIMIT['measurement_fc_max_hz'] * (1 + TOLERANCE_PPM / 1e6):
            self.measurement_seen = True  # a propagation-delay measurement (2.1.2)
        if c is not None and c['version'] == '2.2' and self.short_t_m and fit.below(LIMIT['short_recovery_time_fc_min_hz']):
            self.finding(ss, es, 'fail', 't_m_short_f_c', fmt_hz(f_c), '>= ' + fmt_hz(LIMIT['short_recovery_time_fc_min_hz']),
                         'word 3 selects the short recovery time, which needs a clock of at least 1 MHz')
        if not compensated and not self.measurement_seen:
            minimum = max(2 * data_delay_max(self.cable_m), 1e12 / LIMIT['fc_max_without_compensation_hz'])
            if minimum > 1e12 / LIMIT['fc_max_without_compensation_hz'] and fit.period_below(minimum):
                self.finding(ss, es, 'fail', 'f_c', '%s over %g m' % (fmt_hz(f_c), self.cable_m),
                             'period >= 2 t_D = ' + fmt_time(minimum),
                             'a clock too fast for the cable without delay compensation')
        top = LIMIT['fc_max_with_compensation_hz'] if compensated else LIMIT['fc_max_without_compensation_hz']
        if fit.below(LIMIT['fc_min_hz']) or (fit.above(top) and (not compensated or fit.above(LIMIT['fc_max_special_hz']))):
            high = LIMIT['fc_max_special_hz'] if compensated else top
            self.finding(ss, es, 'fail', 'f_c', fmt_hz(f_c), '%s .. %s' % (fmt_hz(LIMIT['fc_min_hz']), fmt_hz(high)),
                         'clock frequency outside the table\'s range')
        elif fit.above(top):
            self.finding(ss, es, 'fail', 'f_c', fmt_hz(f_c), '<= ' + fmt_hz(top),
                         'above 8 MHz only for special applications with short cables', severity='warning')

    def judge_start_delay(self, f, compensated, f_c):
        '''2.3.2 t_ST (note 8), with delay compensation: FE1 to RE1.'''
        t_st = self.ps(f.rising[0] - f.fe1)
        if not compensated or f_c is None:
            return
        required = required_start_delay(f_c, self.cable_m)
        self.put_ann(f.fe1, f.rising[0], A_CLOCK, ['t_ST %s' % fmt_time(t_st), fmt_time(t_st)])
        self.finding(f.fe1, f.rising[0], self.judge_at_least(t_st, required), 't_st', fmt_time(t_st),
                     '>= ' + fmt_time(required), 'first LOW phase shorter than t_ST for this clock')

    def judge_answer_timing(self, f, period):
        '''2.3.2 t_cal: the start bit on RE11 or later, and within 1 ms (+ T); 2.3.1.1: a later word
        of a continuous clock after at most 7 LOW bits; t_ac for 2.1 parameter frames; and a
        master that stops polling for the start bit while DATA is LOW.'''
        c = f.command
        if c is None:
            return
        s = f.start_bit_clock
        payload = c['payload_bits']
        last_payload = POSITION['turnaround'] - 1 + payload
        T = period or 0
        if s:
            at = f.rising[s - 1]
            if payload:
                if s > last_payload:
                    t_ac = self.ps(at - f.rising[last_payload - 1])
                    bound = LIMIT['memory_access_max_ps'] + T
                    self.put_ann(f.rising[last_payload - 1], at, A_TIMING, ['t_ac %s' % fmt_time(t_ac), fmt_time(t_ac)])
                    self.finding(f.rising[last_payload - 1], at, self.judge_at_most(t_ac, bound), 't_ac', fmt_time(t_ac),
                                 '<= 12 ms + T = ' + fmt_time(bound), 'the acknowledgment came later than the longest '
                                 'memory access time allows')
            else:
                t_cal = self.ps(at - f.fe1)
                self.put_ann(f.fe1, at, A_TIMING, ['t_cal %s (start bit RE%d)' % (fmt_time(t_cal), s), fmt_time(t_cal)])
                if s < POSITION['earliest_start_bit']:
                    self.finding(f.fe1, at, 'fail', 't_cal', 'RE%d' % s, 'RE%d or later' % POSITION['earliest_start_bit'],
                                 'the start bit came before the shortest calculation time')
                bound = LIMIT['calculation_time_max_ps'] + T
                self.finding(f.fe1, at, self.judge_at_most(t_cal, bound), 't_cal', fmt_time(t_cal),
                             '<= 1 ms + T = ' + fmt_time(bound), 'the start bit came later than the longest calculation '
                             'time allows')
            for clock, low in f.low_runs:
                if clock <= len(f.rising) and low > LIMIT['continuous_clock_max_low_bits']:
                    ss = f.rising[max(clock - low, 1) - 1]
                    self.finding(ss, f.rising[clock - 1], 'fail', 't_cal', '%d LOW bits' % low,
                                 '<= %d LOW bits' % LIMIT['continuous_clock_max_low_bits'],
                                 'a later word of the continuous clock came after too many LOW bits (2.3.1.1)')
            return
        # No start bit: a master that stopped clocking while DATA was still LOW gave up polling.
        if f.answer_bits == 0 or not f.low_at_last_rise or len(f.rising) <= POSITION['turnaround'] + 1:
            return
        if payload:
            if len(f.rising) <= last_payload:
                return
            start, check, bound = f.rising[last_payload - 1], 't_ac', LIMIT['memory_access_max_ps']
        else:
            start, check, bound = f.fe1, 't_cal', LIMIT['calculation_time_max_ps']
        polled = self.ps(f.rising[-1] - start)
        self.finding(start, f.rising[-1], self.judge_at_least(polled, bound), check, fmt_time(polled),
                     '>= ' + fmt_time(bound), 'the master stopped polling for the start bit (any compliant encoder may '
                     'take up to %s)' % fmt_time(bound))

    def judge_busy(self, f):
        '''2.5.1, 2.6.1: after a 2.2 memory access (in the command supplement) additional data 1
        shows Busy until it is done: no further access before a frame shows Busy = 0
        (busy_access), and Busy no longer than t_ac max 12 ms + T after it (2.3.2).'''
        key = f.command['key']
        data_ok = all(crc_ok for _, _, crc_ok, _ in f.additional_data)
        ok = f.answer_complete and f.crc_ok and data_ok
        first = [status for status, _, _, _ in f.additional_data
                 if (status & STATUS['information']) < SECOND_DATUM_FROM]
        busy = bool(first[0] & STATUS['busy']) if first else None
        end = f.rising[-1] if f.rising else f.fe1
        if ok and busy is False:
            self.awaiting_not_busy = None
        access_21 = f.command['version'] == '2.1' and key in ACCESSES_21
        access_22 = f.supplement is not None and (key in (RECEIVE_WITH_POSITION, SEND_WITH_POSITION) or
                                                  (key == SELECT_WITH_POSITION and (f.supplement >> 16) not in SELECTING_MRS))
        if (access_21 or access_22) and self.awaiting_not_busy is not None:
            self.finding(f.fe1, end, 'fail', 'busy_access', key, 'a frame with Busy = 0 after the access of frame #%d'
                         % self.awaiting_not_busy, 'a memory access or reset while the encoder may still be busy')
        if access_22:
            self.awaiting_not_busy = f.index
            self.busy_since = end
            self.busy_reported = False
            return
        if f.supplement is not None or self.busy_since is None or not ok or busy is None:
            return
        if not busy:
            self.busy_since = None
            return
        if self.busy_reported:
            return
        busy_for = self.ps(f.fe1 - self.busy_since)
        fit = Fit(f.rising, self.ps_per_sample)
        period = fit.period if fit.period is not None else 0
        bound = LIMIT['memory_access_max_ps'] + period
        decision = self.judge_at_most(busy_for, bound)
        self.finding(self.busy_since, f.fe1, decision, 't_ac', 'busy after ' + fmt_time(busy_for),
                     '<= 12 ms + T = ' + fmt_time(bound), 'the memory access outlasts the longest access time')
        self.busy_reported = decision != 'pass'

    def judge_clock_count(self, f):
        '''2.3.1, 2.4.1, 2.4.2.1: the answer's last bit clocked, one more pulse at most (a
        continuous clock only with 000111); none after a command supplement's last bit.'''
        s = f.start_bit_clock
        c = f.command
        if not s or c is None:
            return
        last_bit = s + f.answer_bits - 1
        clocks = len(f.rising)
        v22 = c['version'] == '2.2'
        parameter = c['payload_bits'] != 0
        ss, es = f.rising[0], f.rising[-1]
        pulses = '%d pulses' % clocks
        if clocks < last_bit:
            self.finding(ss, es, 'fail', 'clock_count', pulses, '>= %d' % last_bit,
                         'the clock stopped before the encoder\'s last bit')
        elif (v22 or parameter) and not c['supplement'] and clocks > last_bit + 1:
            self.finding(ss, es, 'fail', 'clock_count', pulses, '<= %d' % (last_bit + 1),
                         'more clock pulses than required' + (': the encoder discards the access' if parameter else ''),
                         severity='error' if parameter else 'warning')
        elif c['supplement'] and f.supplement_last_clock and clocks > f.supplement_last_clock:
            self.finding(ss, es, 'fail', 'clock_count', pulses, '<= %d (the supplement\'s last bit)'
                         % f.supplement_last_clock, 'more clock pulses than necessary after the command supplement')

    def judge_driver(self, f, period):
        '''2.3.2 t_z (FE1 to the encoder's driver off) and t_OE (the turnaround FE9, or FE33 after a
        2.1 payload, to its driver on, not before), each at most T, one period of the frame's
        clock.'''
        T = period if period else LIMIT['period_at_fc_min_ps']
        if f.release is not None:
            at, _ = f.release
            t_z = self.ps(at - f.fe1)
            self.put_ann(f.fe1, at, A_DRIVER, ['t_z %s' % fmt_time(t_z), fmt_time(t_z)])
            self.finding(f.fe1, at, self.judge_at_most(t_z, T), 't_z', fmt_time(t_z), '<= T = ' + fmt_time(T),
                         'the encoder released DATA too late after FE1')
        if f.drive is None or f.command is None:
            return
        at, falls = f.drive
        turnaround = POSITION['turnaround'] + f.command['payload_bits']
        if falls < turnaround:
            self.finding(at, at, 'fail', 't_oe', 'before FE%d' % turnaround, 'after FE%d' % turnaround,
                         'the encoder drove DATA while the master still sends the mode command')
            return
        fe = f.falling[turnaround - 1]
        t_oe = self.ps(at - fe)
        self.put_ann(fe, at, A_DRIVER, ['t_OE %s' % fmt_time(t_oe), fmt_time(t_oe)])
        self.finding(fe, at, self.judge_at_most(t_oe, T), 't_oe', fmt_time(t_oe), '<= T = ' + fmt_time(T),
                     'the encoder took longer than one clock period after FE%d to drive DATA' % turnaround)

    # ---- the main loop -------------------------------------------------------------------------

    def decode(self):
        if not self.samplerate:
            raise SamplerateError('Cannot decode without samplerate.')
        self.ps_per_sample = 1e12 / self.samplerate
        self.t_m_ps = float(self.options['t_m_us']) * PS_PER_US
        self.t_m = self.samples(self.t_m_ps)
        self.t_m_short_ps = float(self.options['t_m_short_us']) * PS_PER_US
        self.t_r_ps = float(self.options['t_r_ns']) * 1000
        self.ctd = self.samples(float(self.options['clock_to_data_ns']) * 1000)
        self.has_de = has_de = channel_connected(self, 2)
        clk, data, de = self.wait()
        t = self.samplenum
        self.clock_level = clk
        self.data_level = self.base_level = data
        self.last_rise = t
        # A capture is taken to begin at rest when CLOCK is HIGH at its start, unless told it may
        # begin inside a frame: then a frame begins only after CLOCK was HIGH for t_m.
        self.at_rest = self.options['start'] == AT_REST and clk == 1
        enabled = (de == self.de_active) if has_de else None
        conditions = [{0: 'e'}, {1: 'e'}]
        if has_de:
            conditions.append({2: 'e'})
        while True:
            wake = self.timeout()
            if wake is not None:
                skip = max(1, int(wake) + 1 - self.samplenum)
                clk, data, de = self.wait(conditions + [{'skip': skip}])
            else:
                clk, data, de = self.wait(conditions)
            t = self.samplenum
            if data != self.data_level:
                self.on_data(t, data)
            if has_de and (de == self.de_active) != enabled:
                enabled = de == self.de_active
                self.resolve(t)
                self.on_driver(t, enabled)
            if clk != self.clock_level:
                self.on_clock(t, clk)
            elif self.frame is not None:
                self.resolve(t)
                if self.frame_over(t):
                    self.end_frame()


def channel_connected(decoder, index):
    '''has_channel() of libsigrokdecode 0.5.3 (Debian 12) returns True or False without a reference
    of its own, and each call costs the interpreter one; give it back, or PulseView crashes after
    enough decoder runs. A later libsigrokdecode that returns a new reference leaks one count of a
    singleton per run, which does no harm.'''
    connected = decoder.has_channel(index)
    ctypes.pythonapi.Py_IncRef(ctypes.py_object(connected))
    return connected is True


def address_text(command, address, what):
    '''An 8-bit address, MRS code or port address in words where the tables name it.'''
    key = command['key'] if command else ''
    if (what == 'supplement' and key == SELECT_WITH_POSITION) or key == SELECT_AREA:
        if address in SELECTING_MRS:
            info = INFORMATION[address & STATUS['information']]
            stop = address in STOP_MRS
            return 'MRS %s: %s additional data %d' % (hx(address, 2), 'stop' if stop else 'select ' + info['name'] + ' in',
                                                     info['additional_data'])
        if address in AREAS:
            return 'MRS %s: %s' % (hx(address, 2), AREAS[address]['name'])
        return 'MRS ' + hx(address, 2)
    return 'Address ' + hx(address, 2)


def refused_access(f):
    '''A2 type II: a 2.1 parameter frame whose acknowledgment returns the address sent inverted.'''
    return f.payload is not None and f.answer_complete and f.fields['address'][0] == (~(f.payload >> 16) & 0xFF)


def frame_text(f):
    '''The frame as endatsim check --log writes it, without its number and time.'''
    if f.command is None:
        bits = hx(f.mode_bits, 2) if f.mode_bits_seen == POSITION['mode_bits'] else 'incomplete'
        return 'mode bits %s (no mode command), %d clocks' % (bits, f.clocks)
    c = f.command
    s = c['key']
    if f.payload is not None:
        s += ' address %s parameter %s' % (hx(f.payload >> 16, 2), hx(f.payload & 0xFFFF, 4))
    if not f.start_bit_clock:
        return s + ': no start bit, %d clocks' % f.clocks
    s += ': start bit RE%d' % f.start_bit_clock
    if not f.answer_complete:
        return s + ', answer incomplete after %d clocks' % f.clocks
    value = lambda field: f.fields[field][0]
    if c['answer'] == 'position':
        s += ', F1 %d' % value('f1')
        if c['version'] == '2.2':
            s += ' F2 %d' % value('f2')
        s += ', position %d' % value('position')
    elif c['answer'] == 'test_values':
        s += ', test value ' + hx(value('test_value'), 10)
    else:
        s += ', echo %s %s' % (hx(value('address'), 2), hx(value('parameter'), 4))
        if refused_access(f):
            s += ' (type II, A2: the address returned inverted, the access refused)'
    s += ', CRC ' + ('ok' if f.crc_ok else 'BAD')
    for status, data, crc_ok, _ in f.additional_data:
        s += ', additional data I=%d status %s data %s CRC %s' % (status & STATUS['information'], hx(status, 2),
                                                                  hx(data, 4), 'ok' if crc_ok else 'BAD')
    if f.supplement is not None:
        s += ', supplement %s %s' % (hx(f.supplement >> 16, 2), hx(f.supplement & 0xFFFF, 4))
    if f.continuous_words:
        s += ', %d further continuous-clock word(s)' % f.continuous_words
        if f.bad_words:
            s += ' (%d with a BAD CRC)' % f.bad_words
        s += ':' + ';'.join(' position %d CRC %s' % (p, 'ok' if ok else 'BAD') for p, ok in f.words)
        if f.continuous_words > len(f.words):
            s += '; %d more not listed' % (f.continuous_words - len(f.words))
    if f.learnt_position_bits:
        s += '; word 13%s: the position has %d bits' % (' as written, now active' if c['key'] == RESET else '',
                                                          f.learnt_position_bits)
    return s
