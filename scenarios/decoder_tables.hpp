// The tables an EnDat decoder outside endatsim needs, exported as data so that it does not
// retype them: the frame positions and limits of protocol/timing.hpp (D297403 2.3, 2.3.2), the
// mode commands (2.3), the answers' bit layouts (2.3.1, 2.3.5, 2.9), the CRC's generator
// (appendix A4), additional data 1 and 2 (2.3.5, 2.4.2.2), the memory areas' MRS codes (2.4), the
// causes of interface errors and their error handling types (appendix A2),
// the timing table's rows, and the defaults of the checker's frame decoder. The sigrok decoder in
// tools/sigrok/endat/ reads them from tables.py, which `endatsim checks --python` writes (a test
// keeps it in step); `endatsim checks --json` prints the same document.
#pragma once

#include <nlohmann/json.hpp>
#include <string>

namespace endatsim::scenarios {

nlohmann::ordered_json decoder_tables();
// The document as JSON text (two-space indent, a final newline).
std::string decoder_tables_json();
// The document as a Python module: `TABLES`, a dict parsed from the JSON text.
std::string decoder_tables_python();

}  // namespace endatsim::scenarios
