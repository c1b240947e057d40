#include "endatsim/slave/eib.hpp"

#include <algorithm>

namespace endatsim::slave {

namespace pm = protocol::parameters;
using A = MemoryArea;

bool eib_commissioning_area(MemoryArea area) {
  return std::find(kEibCommissioningAreas.begin(), kEibCommissioningAreas.end(), area) != kEibCommissioningAreas.end();
}

bool eib_factory_word(unsigned manufacturer_word) {
  return std::find(kEibFactoryWords.begin(), kEibFactoryWords.end(), manufacturer_word) != kEibFactoryWords.end();
}

MemoryImage eib_factory_image(const EibFactoryData& d) {
  std::vector<std::uint16_t> m(protocol::kManufacturerWords, 0);
  m[word::kOemPartition] = pm::encode_partition_word(d.oem[0], d.oem[1]);
  m[word::kOemPartition + 1] = pm::encode_partition_word(d.oem[2], d.oem[3]);
  m[word::kCompensationPartition] = pm::encode_partition_word(d.compensation[0], d.compensation[1]);
  m[word::kCompensationPartition + 1] = pm::encode_partition_word(d.compensation[2], d.compensation[3]);
  m[word::kEncoderType] = pm::encode_encoder_type(pm::EncoderType::ExternalInterfaceBox);
  const auto id = pm::encode_id_number(d.id);
  std::copy(id.begin(), id.end(), m.begin() + word::kIdNumber);
  const auto serial = pm::encode_serial_number(d.serial);
  std::copy(serial.begin(), serial.end(), m.begin() + word::kSerialNumber);
  m[word::kManufacturerChecksum] = pm::manufacturer_checksum(m);
  MemoryImage img;
  img.areas[A::OperatingStatus] = {0, 0, 0, 0};
  set_manufacturer_words(img, m);
  img.areas[A::OperatingParameters].assign(16, 0);
  const A oem[4] = {A::Oem1, A::Oem2, A::Oem3, A::Oem4};
  const A comp[4] = {A::Compensation1, A::Compensation2, A::Compensation3, A::Compensation4};
  for (unsigned i = 0; i < 4; ++i) {
    if (d.oem[i]) img.areas[oem[i]].assign(d.oem[i]->end + 1, 0);
    if (d.compensation[i]) img.areas[comp[i]].assign(d.compensation[i]->end + 1, 0);
  }
  img.areas[A::ManufacturerEndat22].assign(64, 0);
  img.areas[A::OperatingParameters2].assign(16, 0);
  return img;
}

}  // namespace endatsim::slave
