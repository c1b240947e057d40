# The EnDat tables of endatsim (protocol/, and the defaults of checker/frame_decoder.hpp), as
# `endatsim checks --python` writes them. Do not edit: tests/timing_table_test.cpp fails when this
# file differs from what the tables generate. Regenerate with
#   build/tools/endatsim checks --python > tools/sigrok/endat/tables.py
import json

TABLES = json.loads(r'''
{
  "format": 1,
  "frame_position": {
    "frame_start": 1,
    "master_drives": 2,
    "first_mode_bit": 3,
    "last_mode_bit": 8,
    "mode_bits": 6,
    "turnaround": 9,
    "earliest_start_bit": 11
  },
  "limits": {
    "fc_min_hz": 100000,
    "fc_max_without_compensation_hz": 2000000,
    "fc_max_with_compensation_hz": 8000000,
    "fc_max_special_hz": 16000000,
    "compensated_cable_max_m": 100.0,
    "measurement_fc_min_hz": 100000,
    "measurement_fc_max_hz": 200000,
    "measurement_counter_factor": 8,
    "measurement_counter_tolerance_percent": 10,
    "measurements_min": 3,
    "calculation_time_max_ps": 1000000000,
    "continuous_clock_max_low_bits": 7,
    "memory_access_max_ps": 12000000000,
    "recovery_time_min_ps": 10000000,
    "recovery_time_max_ps": 30000000,
    "short_recovery_time_min_ps": 1250000,
    "short_recovery_time_max_ps": 3750000,
    "short_recovery_time_fc_min_hz": 1000000,
    "recovery_time_2_min_ps": 500000,
    "start_delay_ps": 2000000,
    "start_delay_at_16mhz_ps": 1000000,
    "data_delay_base_ps": 200000,
    "data_delay_per_metre_ps": 10000,
    "data_delay_tolerance_percent": 10,
    "pulse_width_min_ps": 200000,
    "pulse_high_max_ps": 10000000,
    "on_off_ratio_error_percent": 10,
    "period_at_fc_min_ps": 10000000,
    "time_between_cycles_min_ps": 1000000000,
    "error_recovery_wait_ps": 30000000,
    "power_on_t1_min_ps": 800000000000,
    "power_on_t2_min_ps": 80000000000,
    "power_on_t2_max_ps": 120000000000,
    "power_on_pulse_min_ps": 125000,
    "power_on_t3_min_ps": 380000000000,
    "power_on_t3_max_ps": 420000000000
  },
  "crc": {
    "bits": 5,
    "polynomial": 11,
    "preset": 31,
    "final_inversion": true
  },
  "mode_commands": [
    {
      "key": "encoder_send_position_values",
      "name": "Encoder send position values",
      "bits": 7,
      "version": "2.1",
      "payload_bits": 0,
      "answer": "position",
      "supplement": false
    },
    {
      "key": "selection_of_memory_area",
      "name": "Selection of memory area",
      "bits": 14,
      "version": "2.1",
      "payload_bits": 24,
      "answer": "parameter",
      "supplement": false
    },
    {
      "key": "encoder_receive_parameters",
      "name": "Encoder receive parameters",
      "bits": 28,
      "version": "2.1",
      "payload_bits": 24,
      "answer": "parameter",
      "supplement": false
    },
    {
      "key": "encoder_send_parameters",
      "name": "Encoder send parameters",
      "bits": 35,
      "version": "2.1",
      "payload_bits": 24,
      "answer": "parameter",
      "supplement": false
    },
    {
      "key": "encoder_receive_reset",
      "name": "Encoder receive reset",
      "bits": 42,
      "version": "2.1",
      "payload_bits": 24,
      "answer": "parameter",
      "supplement": false
    },
    {
      "key": "encoder_send_test_values",
      "name": "Encoder send test values",
      "bits": 21,
      "version": "2.1",
      "payload_bits": 0,
      "answer": "test_values",
      "supplement": false
    },
    {
      "key": "encoder_receive_test_command",
      "name": "Encoder receive test command",
      "bits": 49,
      "version": "2.1",
      "payload_bits": 24,
      "answer": "parameter",
      "supplement": false
    },
    {
      "key": "encoder_send_position_values_with_additional_data",
      "name": "Encoder send position values with additional data",
      "bits": 56,
      "version": "2.2",
      "payload_bits": 0,
      "answer": "position",
      "supplement": false
    },
    {
      "key": "encoder_send_position_values_and_selection_of_memory_area",
      "name": "Encoder send position values and selection of memory area or of the additional data",
      "bits": 9,
      "version": "2.2",
      "payload_bits": 0,
      "answer": "position",
      "supplement": true
    },
    {
      "key": "encoder_send_position_values_and_receive_parameter",
      "name": "Encoder send position values and receive parameter",
      "bits": 27,
      "version": "2.2",
      "payload_bits": 0,
      "answer": "position",
      "supplement": true
    },
    {
      "key": "encoder_send_position_values_and_send_parameter",
      "name": "Encoder send position values and send parameter",
      "bits": 36,
      "version": "2.2",
      "payload_bits": 0,
      "answer": "position",
      "supplement": true
    },
    {
      "key": "encoder_send_position_values_and_receive_error_reset",
      "name": "Encoder send position values and receive error reset",
      "bits": 45,
      "version": "2.2",
      "payload_bits": 0,
      "answer": "position",
      "supplement": true
    },
    {
      "key": "encoder_send_position_values_and_receive_test_command",
      "name": "Encoder send position values and receive test command",
      "bits": 54,
      "version": "2.2",
      "payload_bits": 0,
      "answer": "position",
      "supplement": true
    },
    {
      "key": "encoder_receive_communication_command",
      "name": "Encoder receive communication command",
      "bits": 18,
      "version": "2.2",
      "payload_bits": 24,
      "answer": "parameter",
      "supplement": false
    }
  ],
  "payload_bits": 24,
  "layouts": {
    "position_2_1": [
      {
        "field": "start_bit",
        "name": "start bit",
        "width": 1,
        "order": "msb_first"
      },
      {
        "field": "f1",
        "name": "F1",
        "width": 1,
        "order": "msb_first"
      },
      {
        "field": "position",
        "name": "position",
        "width": null,
        "order": "lsb_first"
      },
      {
        "field": "crc",
        "name": "CRC",
        "width": 5,
        "order": "msb_first"
      }
    ],
    "position_2_2": [
      {
        "field": "start_bit",
        "name": "start bit",
        "width": 1,
        "order": "msb_first"
      },
      {
        "field": "f1",
        "name": "F1",
        "width": 1,
        "order": "msb_first"
      },
      {
        "field": "f2",
        "name": "F2",
        "width": 1,
        "order": "msb_first"
      },
      {
        "field": "position",
        "name": "position",
        "width": null,
        "order": "lsb_first"
      },
      {
        "field": "crc",
        "name": "CRC",
        "width": 5,
        "order": "msb_first"
      }
    ],
    "test_values": [
      {
        "field": "start_bit",
        "name": "start bit",
        "width": 1,
        "order": "msb_first"
      },
      {
        "field": "f1",
        "name": "F1",
        "width": 1,
        "order": "msb_first"
      },
      {
        "field": "test_value",
        "name": "test value",
        "width": 40,
        "order": "lsb_first"
      },
      {
        "field": "crc",
        "name": "CRC",
        "width": 5,
        "order": "msb_first"
      }
    ],
    "parameter": [
      {
        "field": "start_bit",
        "name": "start bit",
        "width": 1,
        "order": "msb_first"
      },
      {
        "field": "address",
        "name": "address",
        "width": 8,
        "order": "msb_first"
      },
      {
        "field": "parameter",
        "name": "parameter",
        "width": 16,
        "order": "msb_first"
      },
      {
        "field": "crc",
        "name": "CRC",
        "width": 5,
        "order": "msb_first"
      }
    ],
    "payload": [
      {
        "field": "address",
        "name": "address",
        "width": 8,
        "order": "msb_first"
      },
      {
        "field": "parameter",
        "name": "parameter",
        "width": 16,
        "order": "msb_first"
      }
    ],
    "additional_datum": [
      {
        "field": "leading_low",
        "name": "leading low",
        "width": 1,
        "order": "msb_first"
      },
      {
        "field": "status",
        "name": "status",
        "width": 8,
        "order": "msb_first"
      },
      {
        "field": "additional_data",
        "name": "additional data",
        "width": 16,
        "order": "msb_first"
      },
      {
        "field": "crc",
        "name": "CRC",
        "width": 5,
        "order": "msb_first"
      }
    ],
    "supplement": [
      {
        "field": "start_bit",
        "name": "start bit",
        "width": 1,
        "order": "msb_first"
      },
      {
        "field": "address",
        "name": "address",
        "width": 8,
        "order": "msb_first"
      },
      {
        "field": "parameter",
        "name": "parameter",
        "width": 16,
        "order": "msb_first"
      }
    ]
  },
  "additional_data": {
    "datum_bits": 30,
    "status": {
      "warning": 128,
      "reference_mark": 64,
      "busy": 32,
      "information": 31
    },
    "information": [
      {
        "code": 0,
        "key": "nop_1",
        "name": "No data content (NOP)",
        "additional_data": 1
      },
      {
        "code": 1,
        "key": "diagnosis",
        "name": "Diagnosis",
        "additional_data": 1
      },
      {
        "code": 2,
        "key": "position_value_2_word_1",
        "name": "Position value 2 word 1 LSB",
        "additional_data": 1
      },
      {
        "code": 3,
        "key": "position_value_2_word_2",
        "name": "Position value 2 word 2",
        "additional_data": 1
      },
      {
        "code": 4,
        "key": "position_value_2_word_3",
        "name": "Position value 2 word 3 MSB",
        "additional_data": 1
      },
      {
        "code": 5,
        "key": "memory_parameter_lsb",
        "name": "Memory parameters LSB",
        "additional_data": 1
      },
      {
        "code": 6,
        "key": "memory_parameter_msb",
        "name": "Memory parameters MSB",
        "additional_data": 1
      },
      {
        "code": 7,
        "key": "mrs_code_acknowledgment",
        "name": "MRS code acknowledgment",
        "additional_data": 1
      },
      {
        "code": 8,
        "key": "test_command_acknowledgment",
        "name": "Acknowledgment of test command",
        "additional_data": 1
      },
      {
        "code": 9,
        "key": "test_values_word_1",
        "name": "Test values word 1 LSB",
        "additional_data": 1
      },
      {
        "code": 10,
        "key": "test_values_word_2",
        "name": "Test values word 2",
        "additional_data": 1
      },
      {
        "code": 11,
        "key": "test_values_word_3",
        "name": "Test values word 3 MSB",
        "additional_data": 1
      },
      {
        "code": 12,
        "key": "temperature_1",
        "name": "Temperature sensor 1",
        "additional_data": 1
      },
      {
        "code": 13,
        "key": "temperature_2",
        "name": "Temperature sensor 2",
        "additional_data": 1
      },
      {
        "code": 14,
        "key": "additional_sensors",
        "name": "Additional sensors",
        "additional_data": 1
      },
      {
        "code": 15,
        "key": "type3_error_1",
        "name": "Type III error handling (additional data 1)",
        "additional_data": 1
      },
      {
        "code": 16,
        "key": "nop_2",
        "name": "No data content (NOP)",
        "additional_data": 2
      },
      {
        "code": 17,
        "key": "commutation",
        "name": "Commutation",
        "additional_data": 2
      },
      {
        "code": 18,
        "key": "acceleration",
        "name": "Acceleration",
        "additional_data": 2
      },
      {
        "code": 19,
        "key": "commutation_and_acceleration",
        "name": "Commutation & acceleration",
        "additional_data": 2
      },
      {
        "code": 20,
        "key": "limit_position_signals",
        "name": "Limit position signals",
        "additional_data": 2
      },
      {
        "code": 21,
        "key": "limit_position_signals_and_acceleration",
        "name": "Limit position signals & acceleration",
        "additional_data": 2
      },
      {
        "code": 22,
        "key": "asynchronous_position_word_1",
        "name": "Asynchronous position value / position value 2 word 1 LSB",
        "additional_data": 2
      },
      {
        "code": 23,
        "key": "asynchronous_position_word_2",
        "name": "Asynchronous position value / position value 2 word 2",
        "additional_data": 2
      },
      {
        "code": 24,
        "key": "asynchronous_position_word_3",
        "name": "Asynchronous position value / position value 2 word 3 MSB",
        "additional_data": 2
      },
      {
        "code": 25,
        "key": "operating_status_error_sources",
        "name": "Operating status error sources",
        "additional_data": 2
      },
      {
        "code": 26,
        "key": "reserved_26",
        "name": "Currently not assigned",
        "additional_data": 2
      },
      {
        "code": 27,
        "key": "timestamp",
        "name": "Timestamp",
        "additional_data": 2
      },
      {
        "code": 28,
        "key": "reserved_28",
        "name": "Currently not assigned",
        "additional_data": 2
      },
      {
        "code": 29,
        "key": "reserved_29",
        "name": "Currently not assigned",
        "additional_data": 2
      },
      {
        "code": 30,
        "key": "reserved_30",
        "name": "Currently not assigned",
        "additional_data": 2
      },
      {
        "code": 31,
        "key": "type3_error_2",
        "name": "Type III error handling (additional data 2)",
        "additional_data": 2
      }
    ],
    "selecting_mrs": [
      64,
      65,
      66,
      67,
      68,
      69,
      70,
      71,
      72,
      73,
      74,
      75,
      76,
      77,
      78,
      79,
      80,
      81,
      82,
      83,
      84,
      85,
      86,
      87,
      88,
      89,
      90,
      91,
      92,
      93,
      94,
      95
    ],
    "stop_mrs": {
      "1": 79,
      "2": 95
    }
  },
  "memory_areas": [
    {
      "mrs": 185,
      "key": "operating_status",
      "name": "Operating status",
      "endat22_only": false
    },
    {
      "mrs": 161,
      "key": "manufacturer_1",
      "name": "Parameters of the encoder manufacturer (words 4..15)",
      "endat22_only": false
    },
    {
      "mrs": 163,
      "key": "manufacturer_2",
      "name": "Parameters of the encoder manufacturer (words 16..31)",
      "endat22_only": false
    },
    {
      "mrs": 165,
      "key": "manufacturer_3",
      "name": "Parameters of the encoder manufacturer (words 32..47)",
      "endat22_only": false
    },
    {
      "mrs": 167,
      "key": "operating_parameters",
      "name": "Operating parameters",
      "endat22_only": false
    },
    {
      "mrs": 169,
      "key": "oem_1",
      "name": "Parameters of the OEM, area 1",
      "endat22_only": false
    },
    {
      "mrs": 171,
      "key": "oem_2",
      "name": "Parameters of the OEM, area 2",
      "endat22_only": false
    },
    {
      "mrs": 173,
      "key": "oem_3",
      "name": "Parameters of the OEM, area 3",
      "endat22_only": false
    },
    {
      "mrs": 175,
      "key": "oem_4",
      "name": "Parameters of the OEM, area 4",
      "endat22_only": false
    },
    {
      "mrs": 177,
      "key": "compensation_1",
      "name": "Compensation values, area 1",
      "endat22_only": false
    },
    {
      "mrs": 179,
      "key": "compensation_2",
      "name": "Compensation values, area 2",
      "endat22_only": false
    },
    {
      "mrs": 181,
      "key": "compensation_3",
      "name": "Compensation values, area 3",
      "endat22_only": false
    },
    {
      "mrs": 183,
      "key": "compensation_4",
      "name": "Compensation values, area 4",
      "endat22_only": false
    },
    {
      "mrs": 189,
      "key": "manufacturer_endat22",
      "name": "Parameters of the encoder manufacturer for EnDat 2.2",
      "endat22_only": true
    },
    {
      "mrs": 191,
      "key": "section2",
      "name": "Parameters of the section 2 memory area",
      "endat22_only": true
    },
    {
      "mrs": 187,
      "key": "operating_parameters2",
      "name": "Operating parameters 2",
      "endat22_only": true
    },
    {
      "mrs": 96,
      "key": "asynchronous_position",
      "name": "Asynchronous position value",
      "endat22_only": true
    }
  ],
  "error_handling": [
    {
      "cause": 1,
      "type": 1,
      "text": "transfer of mode command disrupted or not supported"
    },
    {
      "cause": 2,
      "type": 2,
      "text": "frame disrupted with MRS code transfer"
    },
    {
      "cause": 3,
      "type": 2,
      "text": "a transmission was not completed (busy error), handed on with the next query"
    },
    {
      "cause": 4,
      "type": 2,
      "text": "010010 received, but not permissible"
    },
    {
      "cause": 5,
      "type": 2,
      "text": "EnDat encoder not yet initiated (EIB)"
    },
    {
      "cause": 6,
      "type": 2,
      "text": "communication command: data driver deactivated at high-impedance with address 0000h"
    },
    {
      "cause": 7,
      "type": 2,
      "text": "currently impermissible memory area selected"
    },
    {
      "cause": 8,
      "type": 2,
      "text": "impermissible or unavailable address, or an access or reset with the busy bit still set"
    },
    {
      "cause": 9,
      "type": 2,
      "text": "writing of parameters into write-protected memory area"
    },
    {
      "cause": 10,
      "type": 2,
      "text": "writing a write-protection bit with 0 after activation"
    },
    {
      "cause": 11,
      "type": 2,
      "text": "impermissible block address selected"
    },
    {
      "cause": 12,
      "type": 2,
      "text": "communication command with unknown address, or an unassigned operating parameter 2 address"
    },
    {
      "cause": 13,
      "type": 3,
      "text": "currently impermissible additional data selected"
    },
    {
      "cause": 14,
      "type": 3,
      "text": "selected additional data not supported (words 0 and 1)"
    },
    {
      "cause": 15,
      "type": 3,
      "text": "several additional data with the same identifier activated"
    },
    {
      "cause": 16,
      "type": 4,
      "text": "an available additional data could not be updated"
    }
  ],
  "position_format": {
    "area_mrs": 161,
    "word": 13,
    "bits_mask": 63
  },
  "function_initialization": {
    "area_mrs": 185,
    "word": 3,
    "short_recovery_time_mask": 3,
    "short_recovery_time_activated": 1
  },
  "decoder": {
    "position_bits": 25,
    "clock_to_data_ps": 60000,
    "t_m_ps": 10000000,
    "supplement_ignore_clocks": 3,
    "fit_max_edges": 4096,
    "f_c_tolerance_ppm": 1000
  },
  "checks": [
    {
      "check": "f_c",
      "symbol": "f_c",
      "designation": "Frequency",
      "section": "2.3.2 note 4, 2.1.1, 2.1.2, 3.9.19",
      "min": "100 kHz",
      "max": "2 MHz without, 8 MHz with delay compensation (16 MHz for special applications)",
      "condition": "fitted over each frame's rising edges from RE2 on; measurement frames have their own row; without compensation also 1 / (2 t_D max) for the cable (2.3.2 note 4 and 2.1.1, Figure 2); this encoder: word 25 (3.9.19), 2 MHz for EnDat 2.1",
      "observed": "encoder pins",
      "evidence": "wires"
    },
    {
      "check": "t_cal",
      "symbol": "t_cal",
      "designation": "Calculation time",
      "section": "2.3.2 note 7, 2.3.1.1",
      "min": "10.5/f_c",
      "max": "1 ms (per encoder)",
      "condition": "minimum as a count: the start bit on RE11 or later; maximum to the rising edge that carries the start bit; continuous clock: at most 7 LOW bits before a later word's start bit; the master polls while DATA is LOW for this encoder's t_cal and the envelope's 1 ms",
      "observed": "encoder pins",
      "evidence": "wires"
    },
    {
      "check": "t_ac",
      "symbol": "t_ac",
      "designation": "Memory access time for read/write parameters",
      "section": "2.3.2, 2.5.1, 2.6.1",
      "min": "0",
      "max": "12 ms (per encoder: the longer of encoder.t_ac_read and encoder.t_ac_write)",
      "condition": "2.1 parameter frames: the last payload bit to the acknowledgment's start bit, and the master polls at least that long (this encoder's t_ac, 12 ms for any encoder); 2.2: Busy in additional data 1 after the command supplement",
      "observed": "encoder pins",
      "evidence": "wires"
    },
    {
      "check": "t_m_t_r",
      "symbol": "t_m, t_R",
      "designation": "Recovery time I and II",
      "section": "2.3.2 notes 3, 5, 9",
      "min": "t_m 10 us (1.25 us short, 2.2 commands) + t_R 500 ns",
      "max": "t_m 30 us (3.75 us short)",
      "condition": "last rising edge of a frame to FE1 of the next, against this encoder's t_m as word 3 activates it and against the envelope's 30 us (3.75 us short) + 500 ns",
      "observed": "encoder pins",
      "evidence": "wires"
    },
    {
      "check": "t_m_short_f_c",
      "symbol": "t_m",
      "designation": "Recovery time I, short",
      "section": "2.3.2 note 3, 3.4.4",
      "min": "f_c >= 1 MHz",
      "max": "",
      "condition": "while word 3 selects 1.25 .. 3.75 us, 2.2 commands need a clock of at least 1 MHz",
      "observed": "encoder pins",
      "evidence": "wires"
    },
    {
      "check": "t_d",
      "symbol": "t_D",
      "designation": "Data delay time",
      "section": "2.3.2 notes 1, 2",
      "min": "0",
      "max": "(0.2 + 0.01 x L) us",
      "condition": "from the rising edge that carried the start bit to the start bit's edge, at the master",
      "observed": "master pins",
      "evidence": "wires"
    },
    {
      "check": "t_st",
      "symbol": "t_ST",
      "designation": "Recovery time III",
      "section": "2.3.2 note 8",
      "min": "2 us (f_c 2 .. 8 MHz), 1 us at 16 MHz",
      "max": "per encoder (encoder.t_st_max)",
      "condition": "FE1 to RE1 with delay compensation; the maximum counts against this encoder",
      "observed": "encoder pins",
      "evidence": "wires"
    },
    {
      "check": "t_hi",
      "symbol": "t_HI",
      "designation": "Positive pulse width",
      "section": "2.3.2",
      "min": "0.2 us without delay compensation",
      "max": "10 us",
      "condition": "every HIGH phase inside a frame; with compensation the on-off ratio row bounds it from below",
      "observed": "encoder pins",
      "evidence": "wires"
    },
    {
      "check": "t_lo",
      "symbol": "t_LO",
      "designation": "Negative pulse width",
      "section": "2.3.2",
      "min": "0.2 us without delay compensation",
      "max": "per encoder (encoder.t_lo_max)",
      "condition": "every LOW phase inside a frame (after t_ST with compensation); with compensation the on-off ratio row bounds it from below; the maximum counts against this encoder",
      "observed": "encoder pins",
      "evidence": "wires"
    },
    {
      "check": "on_off_ratio",
      "symbol": "",
      "designation": "On-off ratio error",
      "section": "2.3.2, 2.1.1",
      "min": "",
      "max": "0 % without (2.1.1: f_c = 1/(2 t_min) for another duty cycle), +/-10 % with delay compensation",
      "condition": "with compensation every HIGH and LOW phase inside a frame (after t_ST) at least 50 % - 10 % of the frame's period T; without, where the cable and not the 2 MHz bounds f_c, the shorter phase t_min at least t_D max for the cable (Figure 2's 1/(2 t_D) read as 1/(2 t_min))",
      "observed": "encoder pins",
      "evidence": "wires"
    },
    {
      "check": "t_z",
      "symbol": "t_z",
      "designation": "Clock low to data inactive",
      "section": "2.3.2 note 6",
      "min": "",
      "max": "T = 1/f_c min",
      "condition": "FE1 to the encoder's driver off",
      "observed": "encoder pins",
      "evidence": "wires"
    },
    {
      "check": "t_oe",
      "symbol": "t_OE",
      "designation": "Clock low to data active",
      "section": "2.3.2 note 6",
      "min": "",
      "max": "T",
      "condition": "FE9 (FE33 after a 2.1 payload) to the encoder's driver on, not before it",
      "observed": "encoder pins",
      "evidence": "wires"
    },
    {
      "check": "t_b",
      "symbol": "t_b",
      "designation": "Time between cycle",
      "section": "2.3.2",
      "min": "> 1 ms (EnDat 2.1 commands)",
      "max": "",
      "condition": "last rising edge to FE1 of a 2.1 memory or parameter frame",
      "observed": "encoder pins",
      "evidence": "wires"
    },
    {
      "check": "delay_measurement_f_c",
      "symbol": "f_c",
      "designation": "Propagation-delay measurement clock",
      "section": "2.1.2",
      "min": "100 kHz",
      "max": "200 kHz",
      "condition": "frames the master declares as measurements",
      "observed": "encoder pins",
      "evidence": "master_declaration"
    },
    {
      "check": "delay_measurement",
      "symbol": "t_D",
      "designation": "Propagation-delay measurement",
      "section": "2.1.2",
      "min": "3 measurements; counter f_e >= 8 f_c - 10 %",
      "max": "",
      "condition": "measured before compensating, again after every change of the transmission path",
      "observed": "master pins",
      "evidence": "master_declaration"
    },
    {
      "check": "delay_measurement_spread",
      "symbol": "t_D",
      "designation": "Propagation-delay measurements agree",
      "section": "2.1.2",
      "min": "3 measurements before compensating",
      "max": "each within T/8 of their mean (T at the compensated f_c)",
      "condition": "the t_D each measurement frame (000111 at 100 .. 200 kHz) shows, judged at the next compensated frame; the latest three or more must agree",
      "observed": "master pins",
      "evidence": "wires"
    },
    {
      "check": "t_d_tolerance",
      "symbol": "t_D",
      "designation": "Set data delay time",
      "section": "2.3",
      "min": "",
      "max": "+/-10 % x T",
      "condition": "the t_D the master compensates with against the line's",
      "observed": "master pins",
      "evidence": "master_declaration"
    },
    {
      "check": "sampling_window",
      "symbol": "t_D",
      "designation": "Data taken at the falling edge plus t_D",
      "section": "2.3, 2.1.2",
      "min": "",
      "max": "",
      "condition": "each declared sampling instant inside its bit's data-valid window",
      "observed": "master pins",
      "evidence": "master_declaration"
    },
    {
      "check": "clock_count",
      "symbol": "",
      "designation": "Number of clock pulses",
      "section": "2.3.1, 2.4.1, 2.4.2.1",
      "min": "the last bit of the answer",
      "max": "one more (continuous clock only with 000111); none after a 2.2 command supplement's last bit",
      "condition": "counted from the start bit; the supplement's last bit as the wires show it",
      "observed": "encoder pins",
      "evidence": "wires"
    },
    {
      "check": "floating_data",
      "symbol": "",
      "designation": "Mode bits and data on a driven line",
      "section": "2.3",
      "min": "",
      "max": "",
      "condition": "DATA undriven while the encoder takes a mode bit (RE3..RE8) or the master samples",
      "observed": "encoder pins",
      "evidence": "wires"
    },
    {
      "check": "bus_contention",
      "symbol": "",
      "designation": "One driver on DATA at a time",
      "section": "2.3, 2.10",
      "min": "",
      "max": "0 ps",
      "condition": "both drivers on at one end's pins",
      "observed": "encoder pins",
      "evidence": "wires"
    },
    {
      "check": "error_recovery",
      "symbol": "t_m",
      "designation": "Recovery after an error handling",
      "section": "A2",
      "min": "30 us (the maximum t_m)",
      "max": "",
      "condition": "last rising edge of a frame with a type I error or no start bit to FE1 of the next",
      "observed": "encoder pins",
      "evidence": "wires"
    },
    {
      "check": "power_on",
      "symbol": "t1, t2, t3",
      "designation": "Power-on conditions",
      "section": "2.3.3",
      "min": "t1 800 ms, t2 80 ms, a LOW pulse > 125 ns or a request cycle, t3 380 ms",
      "max": "t2 120 ms, t3 420 ms",
      "condition": "CLOCK from each switch-on (the run's start, a power interruption, a recorded supply) to the first request",
      "observed": "encoder pins",
      "evidence": "wires"
    },
    {
      "check": "busy_access",
      "symbol": "",
      "designation": "No memory access while Busy",
      "section": "2.5.1, 2.6.1, 2.3.1 note 1",
      "min": "",
      "max": "",
      "condition": "after a 2.2 memory access, no further read, write or reset (2.1 commands included) before a frame whose additional data 1 shows Busy = 0",
      "observed": "encoder pins",
      "evidence": "wires"
    }
  ]
}
''')
