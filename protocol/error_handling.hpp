// Appendix A2: the 16 causes of interface errors and the error handling type each one gets, as
// one table (D297403 4.2).
#pragma once

#include <array>
#include <cstdint>
#include <string_view>

namespace endatsim::protocol {

enum class ErrorType : std::uint8_t { I = 1, II = 2, III = 3, IV = 4 };

// Numbered as in the A2 table.
enum class ErrorCause : std::uint8_t {
  ModeCommandDisrupted = 1,              // or not supported
  MrsFrameDisrupted = 2,                 // MRS code outside the codes of the command's type; too many clocks
  TransmissionNotCompleted = 3,          // "busy error", handed on with the next query
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

// One row of the A2 table.
struct ErrorCauseRow {
  ErrorCause cause;
  ErrorType type;
  std::string_view text;
};

inline constexpr std::array kErrorCauses{
    ErrorCauseRow{ErrorCause::ModeCommandDisrupted, ErrorType::I, "transfer of mode command disrupted or not supported"},
    ErrorCauseRow{ErrorCause::MrsFrameDisrupted, ErrorType::II, "frame disrupted with MRS code transfer"},
    ErrorCauseRow{ErrorCause::TransmissionNotCompleted, ErrorType::II,
                  "a transmission was not completed (busy error), handed on with the next query"},
    ErrorCauseRow{ErrorCause::CommunicationCommandNotPermitted, ErrorType::II, "010010 received, but not permissible"},
    ErrorCauseRow{ErrorCause::EibNotInitialised, ErrorType::II, "EnDat encoder not yet initiated (EIB)"},
    ErrorCauseRow{ErrorCause::DataDriverHighImpedanceBroadcast, ErrorType::II,
                  "communication command: data driver deactivated at high-impedance with address 0000h"},
    ErrorCauseRow{ErrorCause::ImpermissibleMemoryArea, ErrorType::II, "currently impermissible memory area selected"},
    ErrorCauseRow{ErrorCause::ImpermissibleAddress, ErrorType::II,
                  "impermissible or unavailable address, or an access or reset with the busy bit still set"},
    ErrorCauseRow{ErrorCause::WriteProtected, ErrorType::II, "writing of parameters into write-protected memory area"},
    ErrorCauseRow{ErrorCause::WriteProtectionCleared, ErrorType::II,
                  "writing a write-protection bit with 0 after activation"},
    ErrorCauseRow{ErrorCause::ImpermissibleBlockAddress, ErrorType::II, "impermissible block address selected"},
    ErrorCauseRow{ErrorCause::UnknownCommunicationAddress, ErrorType::II,
                  "communication command with unknown address, or an unassigned operating parameter 2 address"},
    ErrorCauseRow{ErrorCause::ImpermissibleAdditionalData, ErrorType::III,
                  "currently impermissible additional data selected"},
    ErrorCauseRow{ErrorCause::UnsupportedAdditionalData, ErrorType::III,
                  "selected additional data not supported (words 0 and 1)"},
    ErrorCauseRow{ErrorCause::DuplicateAdditionalData, ErrorType::III,
                  "several additional data with the same identifier activated"},
    ErrorCauseRow{ErrorCause::AdditionalDataNotUpdated, ErrorType::IV,
                  "an available additional data could not be updated"},
};

namespace detail {
constexpr bool error_causes_in_order() {
  for (std::size_t i = 0; i < kErrorCauses.size(); ++i)
    if (static_cast<std::size_t>(kErrorCauses[i].cause) != i + 1) return false;
  return true;
}
}  // namespace detail
static_assert(detail::error_causes_in_order(), "kErrorCauses holds causes 1 .. 16 in the A2 table's order");

constexpr const ErrorCauseRow& row_of(ErrorCause c) { return kErrorCauses[static_cast<std::size_t>(c) - 1]; }
constexpr ErrorType error_type(ErrorCause c) { return row_of(c).type; }
constexpr std::string_view describe(ErrorCause c) { return row_of(c).text; }

// A2 type II: "the address or parameter is returned inverted" in the acknowledgment of an access
// that raised an error; as sent when it raised none. For 2.1 and 2.2 frames alike (the 2.2
// acknowledgment in additional data 1 carries both, as the 2.1 frame does; docs/model.md §3).
constexpr std::uint8_t acknowledged_address(std::uint8_t address, bool error) {
  return error ? static_cast<std::uint8_t>(~address) : address;
}
constexpr std::uint16_t acknowledged_parameter(std::uint16_t parameter, bool error) {
  return error ? static_cast<std::uint16_t>(~parameter) : parameter;
}

}  // namespace endatsim::protocol
