// Text for XML and SVG attributes and content: the five entities escaped, control characters
// other than tab and line ends dropped (they are not XML), bytes that are not UTF-8 replaced by
// U+FFFD. Used by JUnit results, frame
// diagrams and sweep plots.
#pragma once

#include <string>

namespace endatsim::scenarios {

std::string xml_escape(const std::string& text);

}  // namespace endatsim::scenarios
