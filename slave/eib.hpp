// The External Interface Box (EIB, word 14 type Fh): its memory in factory delivery state and
// what initial commissioning may do before the EIB is initiated (3.5.7, appendix A2 cause 5,
// appendix A10), and the commissioning itself (EibCommissioning), a part of the encoder model.
#pragma once

#include <array>
#include <cstdint>
#include <optional>

#include "endatsim/protocol/parameters.hpp"
#include "endatsim/slave/encoder_params.hpp"
#include "endatsim/slave/memory.hpp"

namespace endatsim::slave {

// 3.5.7: "In the memory area of an EIB ... the encoder type F_hex and the memory size, serial
// number and ID number are saved in factory delivery state." Words 9..12 (memory size, 3.5.5),
// 24..26 (ID number) and 27..29 (serial number) belong to the box: initial commissioning cannot
// change them (choice: they describe the box, not the connected encoder). Word 14 must be
// changed, word 47 follows the words written.
constexpr std::array<unsigned, 10> kEibFactoryWords{
    protocol::word::kOemPartition, protocol::word::kOemPartition + 1,
    protocol::word::kCompensationPartition, protocol::word::kCompensationPartition + 1,
    protocol::word::kIdNumber, protocol::word::kIdNumber + 1, protocol::word::kIdNumber + 2,
    protocol::word::kSerialNumber, protocol::word::kSerialNumber + 1, protocol::word::kSerialNumber + 2};

// What an EIB that is not yet initiated still accepts (A2 cause 5; choice, docs/model-reference.md): selecting,
// reading and writing the areas that initial commissioning fills — the encoder manufacturer's
// words (A1, A3, A5) and, for the A10 scaling of words 27..29, its EnDat 2.2 area (BD). Every
// other memory access is answered with type II, cause 5.
constexpr std::array<MemoryArea, 4> kEibCommissioningAreas{MemoryArea::Manufacturer1, MemoryArea::Manufacturer2,
                                                           MemoryArea::Manufacturer3, MemoryArea::ManufacturerEndat22};
bool eib_commissioning_area(MemoryArea area);
bool eib_factory_word(unsigned manufacturer_word);

struct EibFactoryData {
  protocol::parameters::Partition oem[4] = {image_default::kOemArea, image_default::kOemArea};  // words 9, 10
  protocol::parameters::Partition compensation[4];                                      // words 11, 12
  protocol::parameters::IdNumber id{1'000'000, {'0', '1'}};                             // words 24..26
  protocol::parameters::SerialNumber serial{' ', 10'000'001, ' '};                      // words 27..29
};

// The factory image: word 14 = F001h (type F, NVM bit), the memory size, ID and serial number,
// word 47 their checksum (3.5.26); every other word 0, also the NVM check bits of words 8, 13,
// 30 and 31, which are saved with their words at commissioning. An EnDat 2.2 area (BD, all 0,
// checksum 0) and operating parameters 2 are present: the box answers EnDat 2.2 (A10: "EnDat22"
// with a signal period). Operating status words 0..3 are 0: no write protection set yet.
MemoryImage eib_factory_image(const EibFactoryData& data = {});

// Initial commissioning (3.5.7): while word 14 says EIB, the box is "not yet initiated" (A2
// cause 5) and its commissioning areas stay open; it becomes the connected encoder at a reset or
// when word 14 is written (EncoderParams::eib_activation).
class EibCommissioning {
 public:
  EibCommissioning(const EncoderParams& params, Memory& memory) : params_(params), memory_(memory) {}
  // Word 14 as stored now decides: an EIB type opens commissioning, any other closes it.
  void follow_encoder_type(protocol::parameters::EncoderType type);
  // A2 cause 5 for a memory access outside the commissioning areas while not initiated.
  std::optional<protocol::ErrorCause> refuses(std::optional<MemoryArea> area) const;
  // A position command refused as not supported (EibPositionBeforeCommissioning::NotSupported).
  bool refuses_positions() const;
  // The connected encoder's position width if commissioning completes now: at a reset, or at a
  // write of word 14, as eib_activation says; none while the words written do not describe an
  // encoder the model can be.
  std::optional<unsigned> completes_at_reset() const;
  std::optional<unsigned> completes_at_write(const Selection& s, std::uint8_t address) const;

 private:
  std::optional<unsigned> connected_encoder_bits() const;

  const EncoderParams& params_;
  Memory& memory_;
  bool not_initiated_ = false;
};

}  // namespace endatsim::slave
