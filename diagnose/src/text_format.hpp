#pragma once
// printf-style formatting into a std::string, sized to the result (no fixed buffer that could
// silently truncate a long report line). Shared by the workflow's summary and the report writer.
#include <cstdio>
#include <string>

namespace demfit::diagnose::detail {

template <typename... Args>
std::string format(const char* pattern, Args... args) {
  const int length = std::snprintf(nullptr, 0, pattern, args...);
  if (length <= 0) return {};
  std::string text(static_cast<std::size_t>(length) + 1, '\0');
  std::snprintf(text.data(), text.size(), pattern, args...);
  text.resize(static_cast<std::size_t>(length));
  return text;
}

}  // namespace demfit::diagnose::detail
