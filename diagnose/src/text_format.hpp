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

// How a target's measured model scatter enters the noise model, for the diagnosis's notes and the
// report's scatter column: whitened (with the data's own run counted `data_scatter_ratio` times
// when > 0) or left out below the threshold.
inline std::string scatter_use(bool whitened, double data_scatter_ratio) {
  if (!whitened) return "below the threshold, data noise alone";
  if (data_scatter_ratio > 0.0)
    return format(
        "in the noise model (AR(1) along the curve) for the model run and, x %.3g, for the data's own run; "
        "residuals whitened",
        data_scatter_ratio);
  return "in the noise model (AR(1) along the curve); residuals whitened";
}

}  // namespace demfit::diagnose::detail
