// The one reported interval per variable (see reported_interval.hpp).
#include "demfit/identify/reported_interval.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace demfit::identify {
namespace {

bool flagged(const nlohmann::json& flags, const std::string& variable) {
  return flags.is_array() && std::find(flags.begin(), flags.end(), variable) != flags.end();
}

}  // namespace

ReportedInterval reported_interval(const nlohmann::json& uncertainty, const std::string& variable, double value) {
  ReportedInterval out;
  out.value = value;
  if (!uncertainty.is_object()) return out;
  const nlohmann::json posterior = uncertainty.value("posterior", nlohmann::json());
  if (posterior.is_object() && posterior.contains("variables") && posterior["variables"].contains(variable)) {
    const auto& v = posterior["variables"][variable];
    if (v.value("lower_95", nlohmann::json()).is_number() && v.value("upper_95", nlohmann::json()).is_number()) {
      out.available = true;
      out.method =
          v.value("widened_by_interval_check", false) ? "posterior, widened by interval-end runs" : "posterior";
      out.lower = v["lower_95"].get<double>();
      out.upper = v["upper_95"].get<double>();
      out.identifiable = !v.value("unidentifiable", false);
      if (value < out.lower || value > out.upper) {
        // The answer can sit in the tail of a wide, bound-truncated marginal (GranuDrum quick study:
        // fricr 0.0570 against [0.0578, 0.567]), or off the posterior's centre after a final
        // selection. An interval check steps that side outward from the answer (interval_check.hpp);
        // without one (the check off, or a result stored before) a report must still not print a
        // value outside its own interval, so the interval is widened to it (covering more than 95 %,
        // with no room on that side) and says so.
        out.lower = std::min(out.lower, value);
        out.upper = std::max(out.upper, value);
        out.method += ", widened to the answer";
      }
      return out;
    }
  }
  const nlohmann::json half =
      uncertainty.value("ci_half_width", nlohmann::json::object()).value(variable, nlohmann::json());
  out.identifiable = !flagged(uncertainty.value("unidentifiable", nlohmann::json()), variable);
  if (!half.is_number() || !std::isfinite(half.get<double>())) return out;
  out.available = true;
  out.method = "linearised";
  out.lower = value - half.get<double>();
  out.upper = value + half.get<double>();
  return out;
}

std::string interval_text(const ReportedInterval& interval) {
  if (!interval.available) return "-";
  char text[96];
  std::snprintf(text, sizeof text, "[%.6g, %.6g] (%s)", interval.lower, interval.upper, interval.method.c_str());
  return text;
}

}  // namespace demfit::identify
