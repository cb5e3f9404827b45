// One number as text by a printf pattern ("%.3g"), for the cases' messages and report lines.
#pragma once

#include <cstdio>
#include <string>

namespace demfit::cases {

inline std::string fmt(const char* pattern, double value) {
  char buffer[96];
  std::snprintf(buffer, sizeof buffer, pattern, value);
  return buffer;
}

}  // namespace demfit::cases
