#include "protocol/error_handling.hpp"

namespace endatsim::protocol {

std::string_view describe(ErrorCause c) {
  switch (c) {
    case ErrorCause::ModeCommandDisrupted: return "transfer of mode command disrupted or not supported";
    case ErrorCause::MrsFrameDisrupted: return "frame disrupted with MRS code transfer";
    case ErrorCause::Busy: return "a transmission was not completed (busy error)";
    case ErrorCause::CommunicationCommandNotPermitted: return "010010 received, but not permissible";
    case ErrorCause::EibNotInitialised: return "EnDat encoder not yet initiated (EIB)";
    case ErrorCause::DataDriverHighImpedanceBroadcast:
      return "communication command: data driver deactivated at high-impedance with address 0000h";
    case ErrorCause::ImpermissibleMemoryArea: return "currently impermissible memory area selected";
    case ErrorCause::ImpermissibleAddress: return "impermissible or unavailable address, or busy bit still set";
    case ErrorCause::WriteProtected: return "writing of parameters into write-protected memory area";
    case ErrorCause::WriteProtectionCleared: return "writing a write-protection bit with 0 after activation";
    case ErrorCause::ImpermissibleBlockAddress: return "impermissible block address selected";
    case ErrorCause::UnknownCommunicationAddress: return "communication command with unknown address";
    case ErrorCause::ImpermissibleAdditionalData: return "currently impermissible additional data selected";
    case ErrorCause::UnsupportedAdditionalData: return "selected additional data not supported (words 0 and 1)";
    case ErrorCause::DuplicateAdditionalData: return "several additional data with the same identifier activated";
    case ErrorCause::AdditionalDataNotUpdated: return "an available additional data could not be updated";
  }
  return "?";
}

}  // namespace endatsim::protocol
