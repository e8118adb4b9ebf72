#pragma once
/// A figure in a sentence for a reader: four significant digits (formatNumber keeps the round-trip digits
/// configuration values need; "73.22625598146429 %" is not for reading). The diagnosis's reasons and notes.
#include <string>

namespace lane_keeping {

std::string briefNumber(double x);

}  // namespace lane_keeping
