#pragma once
/// The median of a sample, as the diagnosis and the benchmark read it: with an even count the mean of the two
/// middle values (the upper one alone read a benchmark's 78.9 % median shrink as 79.1 %); 0 for an empty one.
/// By value: the copy is partly reordered (std::nth_element, O(n)).
#include <vector>

namespace lane_keeping {

double median(std::vector<double> values);

}  // namespace lane_keeping
