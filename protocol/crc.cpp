#include "endatsim/protocol/crc.hpp"

#include <boost/crc.hpp>
#include <stdexcept>
#include <vector>

namespace endatsim::protocol {
namespace {

// A4.4.1: "Preload flip-flops via Set with a logical 1", shift, output the inverted register.
boost::crc_basic<kCrcBits> make_generator(const CrcConfig& c = {}) {
  constexpr unsigned kAllOnes = (1U << kCrcBits) - 1;
  return boost::crc_basic<kCrcBits>(kCrcPolynomial, c.preset & kAllOnes, c.final_inversion ? kAllOnes : 0U, false, false);
}

}  // namespace

std::uint8_t crc5(std::span<const std::uint8_t> bits) {
  auto gen = make_generator();
  for (std::uint8_t b : bits) gen.process_bit(b != 0);
  return static_cast<std::uint8_t>(gen.checksum());
}

std::uint8_t make_crc_norm(std::uint8_t param8, std::uint16_t param16, const CrcConfig& config) {
  auto gen = make_generator(config);
  for (int i = 7; i >= 0; --i) gen.process_bit(((param8 >> i) & 1U) != 0);
  for (int i = 15; i >= 0; --i) gen.process_bit(((param16 >> i) & 1U) != 0);
  return static_cast<std::uint8_t>(gen.checksum());
}

std::uint8_t make_crc_pos(unsigned clocks, bool error1, bool error2, bool endat22, std::uint64_t position,
                          const CrcConfig& config) {
  if (clocks > 64) throw std::invalid_argument("make_crc_pos: at most 64 position bits");
  auto gen = make_generator(config);
  gen.process_bit(error1);
  if (endat22) gen.process_bit(error2);
  for (unsigned i = 0; i < clocks; ++i) gen.process_bit(((position >> i) & 1U) != 0);
  return static_cast<std::uint8_t>(gen.checksum());
}

}  // namespace endatsim::protocol
