#include "demfit/identify/model_fingerprint.hpp"

namespace demfit::identify {
namespace {

// A short excerpt of a value for a message (never a whole nested document).
std::string excerpt(const nlohmann::json& value) {
  std::string text = value.is_structured() ? (value.is_object() ? "{...}" : "[...]") : value.dump();
  if (text.size() > 40) text = text.substr(0, 37) + "...";
  return text;
}

}  // namespace

std::string first_difference(const nlohmann::json& before, const nlohmann::json& now, const std::string& path) {
  const std::string here = path.empty() ? "(top level)" : path;
  if (before.is_object() && now.is_object()) {
    for (const auto& item : before.items()) {
      const std::string child = path.empty() ? item.key() : path + "." + item.key();
      if (!now.contains(item.key())) return child + ": was " + excerpt(item.value()) + ", now absent";
      const std::string d = first_difference(item.value(), now.at(item.key()), child);
      if (!d.empty()) return d;
    }
    for (const auto& item : now.items())
      if (!before.contains(item.key()))
        return (path.empty() ? item.key() : path + "." + item.key()) + ": was absent, now " + excerpt(item.value());
    return {};
  }
  if (before.is_array() && now.is_array()) {
    if (before.size() != now.size())
      return here + ": was " + std::to_string(before.size()) + " entries, now " + std::to_string(now.size());
    for (std::size_t i = 0; i < before.size(); ++i) {
      const std::string d = first_difference(before[i], now[i], path + "[" + std::to_string(i) + "]");
      if (!d.empty()) return d;
    }
    return {};
  }
  if (before != now) return here + ": was " + excerpt(before) + ", now " + excerpt(now);
  return {};
}

}  // namespace demfit::identify
