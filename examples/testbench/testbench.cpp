// An EnDat testbench outside the endatsim tree: its own master — a few lines of bit-banging
// on the master side of the line, as firmware or an FPGA state machine would do it — reads
// positions from endatsim's encoder model over 25 m of cable at 1 MHz, checks the CRC, and
// lets endatsim's checker judge the timing on the pins. Exit status 0 when every read matches
// the position the encoder latched and the checker found nothing.
// Headers are named <endatsim/PART/...>, as inside the tree.
#include <endatsim/checker/timing_checker.hpp>
#include <endatsim/protocol/protocol.hpp>
#include <endatsim/slave/slave.hpp>

#include <cstdio>
#include <vector>

using namespace endatsim;

namespace {

// "Encoder send position values" (000111, an EnDat 2.1 command) without delay compensation:
// DATA is sampled at the falling edges; start bit, F1, position LSB first, CRC MSB first.
class MyMaster {
 public:
  MyMaster(sim::Kernel& kernel, line::Line& line, checker::TimingChecker& monitor)
      : kernel_(kernel), pins_(line.master()), monitor_(monitor) {}

  void read(unsigned frames, sim::Time cycle) {
    frames_left_ = frames;
    cycle_ = cycle;
    kernel_.schedule(sim::us(1), sim::bind<&MyMaster::start_frame>(this));
  }
  const std::vector<std::uint64_t>& positions() const { return positions_; }
  unsigned crc_errors() const { return crc_errors_; }

  static constexpr sim::Hertz kClock = sim::MHz(1);
  static constexpr unsigned kPositionBits = 25;

 private:
  void start_frame() {
    frame_ = checker::DeclaredFrame{};
    frame_.index = index_++;
    frame_.start = kernel_.now();
    frame_.command = protocol::ModeCommand::EncoderSendPositionValues;
    frame_.mode_bits = 0b000111;
    frame_.f_c = kClock;
    frame_.answer_bits = 1 + kWordBits;  // what the master expects: start bit .. CRC
    clock_ = 0;
    start_bit_ = 0;
    seen_low_ = false;
    bits_.clear();
    monitor_.on_frame_start(frame_);
    falling();
  }

  void falling() {
    ++clock_;
    pins_.clock_out.write(false);
    if (clock_ == 2) {  // driver on with a dummy 0
      pins_.data_enable.write(true);
      pins_.data_out.write(false);
    } else if (clock_ >= 3 && clock_ <= 8) {  // mode bits, M2 first
      pins_.data_out.write(((frame_.mode_bits >> (8 - clock_)) & 1U) != 0);
    } else if (clock_ == 9) {  // turnaround: the encoder drives from here
      pins_.data_enable.write(false);
    } else if (clock_ > 9) {
      sample(clock_ - 1);  // the bit the encoder sent after the previous rising edge
    }
    kernel_.schedule(half_period(), sim::bind<&MyMaster::rising>(this));
  }

  void sample(unsigned slot) {
    const bool level = pins_.data_in.read();
    monitor_.on_sample(frame_, slot);
    if (start_bit_ == 0) {
      seen_low_ = seen_low_ || !level;
      if (seen_low_ && level) {
        start_bit_ = slot;
        frame_.start_bit_clock = slot;
      }
      return;
    }
    if (bits_.size() < kWordBits) bits_.push_back(level ? 1 : 0);
  }

  void rising() {
    pins_.clock_out.write(true);
    frame_.end = kernel_.now();
    // One pulse more after the last bit, whose falling edge samples it.
    const bool done = start_bit_ != 0 && clock_ >= start_bit_ + kWordBits + 1;
    if (!done && clock_ < 2000) {
      kernel_.schedule(half_period(), sim::bind<&MyMaster::falling>(this));
      return;
    }
    finish_frame();
  }

  void finish_frame() {
    if (bits_.size() == kWordBits) {
      // F1, then the position LSB first, then the CRC MSB first.
      const bool error1 = bits_[0] != 0;
      std::uint64_t position = 0;
      for (unsigned i = 0; i < kPositionBits; ++i) position |= std::uint64_t{bits_[1 + i]} << i;
      std::uint8_t crc = 0;
      for (unsigned i = 0; i < 5; ++i) crc = static_cast<std::uint8_t>(crc << 1 | bits_[1 + kPositionBits + i]);
      frame_.ok = crc == protocol::make_crc_pos(kPositionBits, error1, true, false, position);
      if (frame_.ok) positions_.push_back(position);
      else ++crc_errors_;
    }
    frame_.error_handling = start_bit_ == 0;  // A2: the next frame waits the longest t_m
    monitor_.on_frame_end(frame_);
    if (--frames_left_ > 0) kernel_.schedule(cycle_ - (kernel_.now() - frame_.start), sim::bind<&MyMaster::start_frame>(this));
  }

  sim::Time half_period() const { return sim::period_of(kClock) / 2; }

  static constexpr unsigned kWordBits = 1 + kPositionBits + 5;  // F1, position, CRC

  sim::Kernel& kernel_;
  line::Line::MasterSide pins_;
  checker::TimingChecker& monitor_;
  checker::DeclaredFrame frame_;
  std::uint64_t index_ = 0;
  unsigned frames_left_ = 0;
  sim::Time cycle_{0};
  unsigned clock_ = 0;
  unsigned start_bit_ = 0;
  bool seen_low_ = false;
  std::vector<std::uint8_t> bits_;
  std::vector<std::uint64_t> positions_;
  unsigned crc_errors_ = 0;
};

}  // namespace

int main() {
  sim::Kernel kernel;
  line::LineParams line_params;
  line_params.cable_length_m = 25;
  line::Line line(kernel, line_params);

  slave::EncoderParams encoder_params;  // 25-bit singleturn EnDat 2.2 encoder
  encoder_params.motion.start = 1'000'000;
  encoder_params.motion.counts_per_s = 2'000'000;  // a turning axis
  slave::Encoder encoder(kernel, line, encoder_params);

  // The checker watches the pins. It is told what the encoder's datasheet declares (here the
  // model's own values) and what the master intends (1 MHz, no compensation); the master also
  // declares its frames and sampling instants, so that the sampling window is judged too.
  checker::EncoderDeclaration datasheet;
  datasheet.position_bits = encoder_params.position_bits;
  datasheet.output_delay = encoder_params.output_delay;
  datasheet.t_cal = encoder_params.t_cal;
  datasheet.t_m = encoder_params.t_m;
  datasheet.t_r = encoder_params.t_r;
  checker::MasterDeclaration declared;
  declared.f_c = MyMaster::kClock;
  declared.position_bits = MyMaster::kPositionBits;
  checker::TimingChecker checker(kernel, line, datasheet, declared);

  MyMaster master(kernel, line, checker);
  master.read(8, sim::us(100));
  kernel.run(sim::ms(2));
  checker.finish();

  int failures = 0;
  const auto& latched = encoder.frames();
  std::printf("%zu reads, %u CRC errors, %zu encoder frames\n", master.positions().size(), master.crc_errors(),
              latched.size());
  if (master.positions().size() != 8 || latched.size() != 8) ++failures;
  for (std::size_t i = 0; i < master.positions().size() && i < latched.size(); ++i) {
    const bool same = master.positions()[i] == latched[i].position;
    std::printf("  frame %zu: read %llu, encoder latched %llu%s\n", i, static_cast<unsigned long long>(master.positions()[i]),
                static_cast<unsigned long long>(latched[i].position), same ? "" : "  MISMATCH");
    failures += same ? 0 : 1;
  }
  for (const auto& v : checker.violations()) {
    std::printf("  violation %s at %s: measured %s, limit %s - %s\n", v.check.c_str(), sim::format_time(v.time).c_str(),
                v.measured.c_str(), v.limit.c_str(), v.message.c_str());
    ++failures;
  }
  std::printf(failures == 0 ? "testbench passed\n" : "testbench FAILED\n");
  return failures == 0 ? 0 : 1;
}
