#include "lane_keeping/common/brief_number.h"

#include <cstdio>

namespace lane_keeping {

std::string briefNumber(double x) {
  char text[32];
  std::snprintf(text, sizeof(text), "%.4g", x);
  return text;
}

}  // namespace lane_keeping
