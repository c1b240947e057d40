##
## This file is part of endatsim.
##

'''
EnDat 2.2 (HEIDENHAIN) is a bidirectional synchronous serial interface for position encoders:
the master (subsequent electronics) drives CLOCK; DATA carries the master's mode command and the
encoder's answer in turn (specification D297403).

This decoder reads CLOCK and DATA at the encoder's connector, as endatsim's checker does: the
master's bits on rising CLOCK edges, the encoder's bit of slot k in the middle of its
data-valid window (half-way between RE_k and RE_k+1, plus the encoder's CLOCK-to-DATA delay).
It decodes mode commands, 2.1 parameter payloads, start bit, F1/F2, position, test values,
parameter echoes, CRC (appendix A4), additional data 1 and 2 with their status bits and the 2.2
command supplement, and judges the rows of the timing table (2.3.2) that the wires show. The
optional DATA driver enable (the encoder's) adds t_z and t_OE.

The limits, mode commands, bit layouts and the CRC come from endatsim's own tables
(tables.py, written by `endatsim checks --python`).

Options: the position's width (until a read of word 13 shows the encoder's own), the encoder's
CLOCK-to-DATA delay, its recovery time t_m (a CLOCK HIGH that long ends a frame), the cable
length (for f_c without delay compensation and t_ST) and whether the capture begins at rest.
'''

from .pd import Decoder
