// The master's scenario parameters, one row per scalar key (sim/parameter.hpp): "master" and its
// objects "power_on", "delay_measurement", "careful", "safety" and "diagnostics". The loader reads
// the keys through these rows, the validate() functions check the same ranges, and the schema's
// properties and docs/parameters.md are generated from them.
#include <array>
#include <type_traits>
#include <utility>

#include "endatsim/master/master.hpp"
#include "endatsim/protocol/diagnosis.hpp"
#include "endatsim/protocol/timing.hpp"

namespace endatsim::master {
namespace {

using sim::row_bound;
// The widest position the models take, and a range of positions or steps as wide.
constexpr std::int64_t kPositionMax = (std::int64_t{1} << protocol::kPositionBitsMax) - 1;

using sim::enum_choice;

constexpr std::array<std::string_view, 2> kStartBitDetections{"wait_low_then_high", "first_high"};
static_assert(static_cast<std::size_t>(StartBitDetection::FirstHigh) == 1);
constexpr std::array<std::string_view, 2> kCounterPhases{"free_running", "edge_aligned"};
static_assert(static_cast<std::size_t>(CounterPhase::EdgeAligned) == 1);

using M = MasterParams;
const std::array kMaster{
    sim::Parameter<M>{"f_c", sim::FrequencyField<M>{&M::f_c}, M::kMinFc, M::kMaxFc, "2.3.2 note 4",
                      "The clock frequency of the frames (16 MHz is the model's limit; the checker judges the spec's).",
                      true},
    sim::Parameter<M>{"t_st", &M::t_st, 0, row_bound(sim::ms(1)), "2.3.2 note 8",
                      "The first LOW phase stretched to this t_ST; 0: not stretched."},
    sim::Parameter<M>{"jitter", &M::jitter, 0, row_bound(sim::us(100)), "",
                      "Peak edge jitter, uniform and seeded; below half the shorter clock phase."},
    sim::Parameter<M>{"delay_compensation", &M::delay_compensation, 0, 0, "2.1.2",
                      "Measure t_D and sample each bit t_D after its falling edge."},
    sim::Parameter<M>{"fixed_t_d", &M::fixed_t_d, 0, row_bound(sim::us(10)), "2.1.2",
                      "A delay set by hand instead of measured; compensation uses it from the first frame."},
    sim::Parameter<M>{"position_bits", &M::position_bits, 1, protocol::kPositionBitsMax, "3.5.6", "Word 13 as the master has it configured."},
    sim::Parameter<M>{"extra_clock_after_last_bit", &M::extra_clock_after_last_bit, 0, 0, "2.3",
                      "One more clock pulse after the last bit, whose falling edge samples it; false: the last bit is "
                      "sampled half a period after the last rising edge."},
    sim::Parameter<M>{"t_m_wait", &M::t_m_wait, 0, row_bound(sim::ms(100)), "2.3.2",
                      "CLOCK held HIGH after a frame: at least the encoder's t_m."},
    sim::Parameter<M>{"t_r_wait", &M::t_r_wait, 0, row_bound(sim::ms(100)), "2.3.2", "Then t_R before the next FE1."},
    sim::Parameter<M>{"error_wait", &M::error_wait, 0, row_bound(sim::ms(100)), "A2",
                      "The wait after an error handling (\"the maximum t_m of 30 us must be waited\")."},
    sim::Parameter<M>{"reset_wait", &M::reset_wait, 0, row_bound(sim::ms(100)), "2.7",
                      "The wait after \"Encoder receive reset\" (the start-up routine of the German brochure, older edition, waits 50 ms)."},
    sim::Parameter<M>{"t_b_wait", &M::t_b_wait, 0, row_bound(sim::ms(100)), "2.3.2",
                      "The wait before a 2.1 memory or parameter frame after the previous frame (t_b > 1 ms)."},
    sim::Parameter<M>{"adopt_word13", &M::adopt_word13, 0, 0, "3.5.6",
                      "The start-up routine reads word 13 and clocks that many position bits from then on."},
    sim::Parameter<M>{"startup_f_c", sim::FrequencyField<M>{&M::startup_f_c}, M::kMinFc, M::kMaxFc, "2.1.2",
                      "The clock of the start-up routine: before t_D is known only a slow clock is safe on a long cable."},
    sim::Parameter<M>{"start_bit_timeout", &M::start_bit_timeout, 1, row_bound(sim::ms(100)), "2.3.2",
                      "Polling for the start bit gives up after this (t_cal max)."},
    sim::Parameter<M>{"memory_access_timeout", &M::memory_access_timeout, 1, row_bound(sim::ms(100)), "2.3.2",
                      "2.1 parameter frames: polling after the 24 bits gives up after this (t_ac max + 1 ms)."},
    sim::Parameter<M>{"type1_detect_samples", &M::type1_detect_samples, 1, 64, "A2",
                      "HIGH samples after the turnaround without a LOW that mean a type I error handling."},
    sim::Parameter<M>{"supplement_lead_bits", &M::supplement_lead_bits, 1, 32, "2.4.2",
                      "LOW bits before the start bit of a 2.2 command supplement (as a published master drives them, 7)."},
    sim::Parameter<M>{"supplement_driven_lead_bits", &M::supplement_driven_lead_bits, 1, 32, "2.4.2",
                      "Of those, the last ones the master drives; before them DATA is left undriven so that the "
                      "encoder's release crosses the cable first; at most supplement_lead_bits."},
    sim::Parameter<M>{"start_bit_detection",
                      enum_choice<M, &M::start_bit_detection, kStartBitDetections>(), 0, 0, "2.3",
                      "How the master finds the start bit: wait for the encoder's LOW, then a HIGH; or the first HIGH "
                      "sample after the mode bits."},
};

using P = MasterParams::PowerOnSequence;
const std::array kPowerOn{
    sim::Parameter<P>{"t1_t2", &P::t1_t2, 0, row_bound(sim::ms(10'000)), "2.3.3",
                      "After switching on, CLOCK at a valid level (t1 >= 800 ms) and HIGH (t2 = 80 .. 120 ms)."},
    sim::Parameter<P>{"pulse", &P::pulse, 1, row_bound(sim::ms(1)), "2.3.3", "Then at least one LOW pulse > 125 ns."},
    sim::Parameter<P>{"t3", &P::t3, 0, row_bound(sim::ms(10'000)), "2.3.3",
                      "Then CLOCK HIGH for t3 = 380 .. 420 ms before the first request."},
};

using D = DelayMeasurementParams;
const std::array kDelayMeasurement{
    sim::Parameter<D>{"f_c", sim::FrequencyField<D>{&D::f_c}, sim::kHz(10), MasterParams::kMaxFc, "2.1.2",
                      "The reduced clock of the measurement frames (the spec's: 100 .. 200 kHz)."},
    sim::Parameter<D>{.key = "f_e",
                      .field = sim::FrequencyField<D>{&D::f_e},
                      .min = sim::MHz(1),
                      .max = sim::MHz(2000),
                      .section = "2.1.2",
                      .help = "The counter clock; 0: eight times the intended f_c (\"at least eight times\").",
                      .zero_allowed = true},
    sim::Parameter<D>{"count", &D::count, 1, 100, "2.1.2", "Measurements averaged (at least three)."},
    sim::Parameter<D>{"max_rounds", &D::max_rounds, 1, 100, "2.1.2",
                      "Rounds in all when a value strays more than T/8 from the mean."},
    sim::Parameter<D>{"counter_phase", enum_choice<D, &D::counter_phase, kCounterPhases>(), 0, 0, "2.1.2",
                      "The f_e counter on its own oscillator (free_running: counts scatter by one, their mean unbiased) "
                      "or restarted with the edge (edge_aligned: truncates; half a count is added)."},
};

using C = CarefulMaster;
const std::array kCareful{
    sim::Parameter<C>{"retries", &C::retries, 0, 10, "", "A failed frame of a script operation is repeated up to this often."},
    sim::Parameter<C>{"verify_echo", &C::verify_echo, 0, 0, "2.6",
                      "2.1 parameter frames: an echo other than what was sent fails."},
    sim::Parameter<C>{"remeasure_after_line_change", &C::remeasure_after_line_change, 0, 0, "2.1.2",
                      "With delay compensation, measure t_D again after a change of the transmission path."},
    sim::Parameter<C>{"remeasure_after_power_interruption", &C::remeasure_after_power_interruption, 0, 0, "2.1.2",
                      "... and after a power interruption."},
    sim::Parameter<C>{"remeasure_after_crc_errors", &C::remeasure_after_crc_errors, 0, 1000, "",
                      "... and after this many failed frames in a row; 0: never."},
    sim::Parameter<C>{"reselect_after_power_interruption", &C::reselect_after_power_interruption, 0, 0, "2.4.2.2",
                      "Select the additional data again after a power interruption (the encoder forgot them)."},
};

using S = SafetyParams;
const std::array kSafety{
    sim::Parameter<S>{"error_messages", &S::error_messages, 0, 0, "2.3.1", "F1 and F2 evaluated separately; off: F1 only."},
    sim::Parameter<S>{"read_error_sources", &S::read_error_sources, 0, 0, "3.4.1",
                      "With error_messages: read word 0 when an error message appears."},
    sim::Parameter<S>{"position_value_2", &S::position_value_2, 0, 0, "2.3.5.1",
                      "Position value 2 compared with position value 1 against the encoder's stored accuracy."},
    sim::Parameter<S>{"forced_dynamic_sampling", &S::forced_dynamic_sampling, 0, 0, "3.5.3",
                      "Force error messages 1 and 2 with test commands and verify them."},
    sim::Parameter<S>{"forced_error1_port", &S::forced_error1_port, 0, 0xFF, "3.5.3",
                      "The port address that forces error message 1 (the table lost a column)."},
    sim::Parameter<S>{"forced_error2_port", &S::forced_error2_port, 0, 0xFF, "3.5.3",
                      "The port address that forces error message 2."},
    sim::Parameter<S>{"forced_sampling_deadline", &S::forced_sampling_deadline, 1, row_bound(sim::ms(100)), "3.5.3",
                      "A forced error must show \"with one of the next EnDat 2.2 queries (< 1 ms)\"."},
    sim::Parameter<S>{"crc_self_test", &S::crc_self_test, 0, 0, "A4",
                      "The master's CRC evaluation fed with sequences of known result."},
    sim::Parameter<S>{"startup_positions", &S::startup_positions, 0, 0, "",
                      "Multiple transmission of the position value at start-up before the axis is released."},
    sim::Parameter<S>{"startup_repetitions", &S::startup_repetitions, 2, 100, "",
                      "Consecutive values that must agree before release (a comparison needs two)."},
    sim::Parameter<S>{"startup_max_reads", &S::startup_max_reads, 2, 10'000, "",
                      "Reads before the axis stays blocked; at least startup_repetitions."},
    sim::Parameter<S>{"startup_tolerance", &S::startup_tolerance, 0, kPositionMax, "",
                      "LSB two consecutive values may differ by, beyond the set-point's motion."},
    sim::Parameter<S>{"checksums", &S::checksums, 0, 0, "3.5.26", "Words 47 (3.5.26) and 63 (3.9.37) verified."},
    sim::Parameter<S>{"acknowledgements", &S::acknowledgements, 0, 0, "2.6.1",
                      "Echoes (2.6) and I = 5 / 6 acknowledgments compared with what was written."},
    sim::Parameter<S>{"following_error", &S::following_error, 0, 0, "", "Servo lag against the set-point."},
    sim::Parameter<S>{"following_error_limit", &S::following_error_limit, 1, kPositionMax, "", "The servo lag allowed, in LSB."},
    sim::Parameter<S>{"command_set", &S::command_set, 0, 0, "2.3",
                      "Word 37 read at start-up; an encoder supporting the communication command is refused (3.5.22)."},
};

using G = DiagnosticsParams;
const std::array kDiagnostics{
    sim::Parameter<G>{"enabled", &G::enabled, 0, 0, "A3", "Collect the diagnosis for a service engineer."},
    sim::Parameter<G>{"temperatures", &G::temperatures, 0, 0, "2.3.5.1",
                      "Temperature 1 and 2 in the rotation of additional data 1."},
    sim::Parameter<G>{"additional_sensors", &G::additional_sensors, 0, protocol::diagnosis::kAdditionalSensorAddresses, "2.3.5.1",
                      "Interrogations of the additional sensors per round (a 4-bit address)."},
    sim::Parameter<G>{"reserve_limit", &G::reserve_limit, 0, 255, "A3",
                      "A valuation number below it is a low function reserve (a guess: A3 gives no scaling)."},
    sim::Parameter<G>{"read_warnings", &G::read_warnings, 0, 0, "3.4.2", "WRN set: read word 1 of the operating status."},
    sim::Parameter<G>{"warnings_interval", &G::warnings_interval, 0, row_bound(sim::ms(60'000)), "3.4.2",
                      "Read word 1 again this often while WRN stays set; 0: only when WRN appears."},
};

const std::array kCrcCheck{
    sim::Parameter<CrcCheck>{"endat22_rule_for_21", &CrcCheck::endat22_rule_for_21, 0, 0, "A4",
                             "2.1 frames checked with F2 included, as 2.2 frames are (a fault)."},
    sim::Parameter<CrcCheck>{"table_fault_width", &CrcCheck::table_fault_width, 0, protocol::kPositionBitsMax, "",
                             "A table-driven CRC whose loop ends one bit early at this position width; 0: none (a "
                             "fault)."},
    sim::Parameter<CrcCheck>{"accept_any", &CrcCheck::accept_any, 0, 0, "",
                             "A comparator stuck at 'equal': every CRC passes (a fault the CRC self-test catches)."},
};

const std::array kSetpoint{
    sim::Parameter<MotionSetpoint>{"start", &MotionSetpoint::start, 0, kPositionMax, "",
                                   "The commanded position at time 0, in measuring steps."},
    sim::Parameter<MotionSetpoint>{"counts_per_s", &MotionSetpoint::counts_per_s, -(kPositionMax + 1), kPositionMax + 1, "",
                                   "The commanded velocity in measuring steps per second."},
};

}  // namespace

std::span<const sim::Parameter<CrcCheck>> crc_check_parameters() { return kCrcCheck; }
std::span<const sim::Parameter<MotionSetpoint>> setpoint_parameters() { return kSetpoint; }
std::span<const sim::Parameter<MasterParams>> master_parameters() { return kMaster; }
std::span<const sim::Parameter<MasterParams::PowerOnSequence>> power_on_parameters() { return kPowerOn; }
std::span<const sim::Parameter<DelayMeasurementParams>> delay_measurement_parameters() { return kDelayMeasurement; }
std::span<const sim::Parameter<CarefulMaster>> careful_parameters() { return kCareful; }
std::span<const sim::Parameter<SafetyParams>> safety_parameters() { return kSafety; }
std::span<const sim::Parameter<DiagnosticsParams>> diagnostics_parameters() { return kDiagnostics; }

}  // namespace endatsim::master
