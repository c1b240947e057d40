// Appendix A2: the 16 causes of interface errors and the error handling type each one gets.
#pragma once

#include <cstdint>
#include <string_view>

namespace endatsim::protocol {

enum class ErrorType : std::uint8_t { I = 1, II = 2, III = 3, IV = 4 };

// Numbered as in the A2 table.
enum class ErrorCause : std::uint8_t {
  ModeCommandDisrupted = 1,              // or not supported
  MrsFrameDisrupted = 2,                 // MRS code outside the codes of the command's type; too many clocks
  Busy = 3,                              // a transmission was not completed
  CommunicationCommandNotPermitted = 4,  // 010010 received, but not permissible
  EibNotInitialised = 5,
  DataDriverHighImpedanceBroadcast = 6,  // communication command: driver high-impedance with address 0000h
  ImpermissibleMemoryArea = 7,           // BB, BD, BF only with a 2.2 mode command; areas that do not exist
  ImpermissibleAddress = 8,              // also: reset or access with the busy bit still set
  WriteProtected = 9,
  WriteProtectionCleared = 10,           // writing 0 to a write-protection bit once it is active
  ImpermissibleBlockAddress = 11,
  UnknownCommunicationAddress = 12,      // also: unassigned operating parameter 2 address
  ImpermissibleAdditionalData = 13,      // I = 26, 28, 29, 30
  UnsupportedAdditionalData = 14,        // not in words 0/1 of the EnDat 2.2 manufacturer area
  DuplicateAdditionalData = 15,
  AdditionalDataNotUpdated = 16,
};

constexpr ErrorType error_type(ErrorCause c) {
  const auto n = static_cast<unsigned>(c);
  if (n == 1) return ErrorType::I;
  if (n <= 12) return ErrorType::II;
  if (n <= 15) return ErrorType::III;
  return ErrorType::IV;
}

std::string_view describe(ErrorCause c);

}  // namespace endatsim::protocol
