// Built without libzip: a sigrok session (a zip archive) cannot be opened, and says so. The VCD
// and CSV readers work as always; PulseView and sigrok-cli export either.
#include "endatsim/capture/capture.hpp"

namespace endatsim::capture {

std::unique_ptr<Reader> open_sigrok(const std::string& path) {
  throw CaptureError(path + ": a sigrok session, but this endatsim was built without libzip, which reads them "
                            "(install libzip-dev and build again, or export the capture as VCD or CSV)");
}

}  // namespace endatsim::capture
