#pragma once
/// A printf format into a std::string of whatever length it takes: the findings and notes the diagnosis writes
/// with their numbers (input checks, the sensors' agreement, the straights' steering).
#include <string>

namespace lane_keeping {

std::string printfString(const char* format, ...) __attribute__((format(printf, 1, 2)));

}  // namespace lane_keeping
