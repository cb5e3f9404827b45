#include "json_reader.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "demfit/identify/json_document.hpp"

namespace demfit::identify::detail {

JsonReader::JsonReader(const nlohmann::json& object, std::string path) : object_(object), path_(std::move(path)) {
  if (!object_.is_object())
    throw std::runtime_error("study: " + (path_.empty() ? std::string("top level") : path_) +
                             ": expected a JSON object {...}");
}

void JsonReader::fail(const std::string& key, const std::string& problem) const {
  throw std::runtime_error("study: " + field(key) + ": " + problem);
}

namespace {

// Edit distance, to point at a misspelt key when a required one is missing.
std::size_t edit_distance(const std::string& a, const std::string& b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t up = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diagonal = up;
    }
  }
  return row[b.size()];
}

}  // namespace

const nlohmann::json& JsonReader::raw(const std::string& key) {
  if (!object_.contains(key)) {
    for (const auto& item : object_.items())
      if (!used_.count(item.key()) && edit_distance(item.key(), key) <= 2)
        fail(item.key(), "unknown key; did you mean \"" + key + "\"? (see docs/study_format.md)");
    fail(key, "missing; this field is required");
  }
  used_.insert(key);
  return object_.at(key);
}

double JsonReader::number(const std::string& key) {
  const auto& value = raw(key);
  if (!value.is_number()) fail(key, "expected a number, got " + json_excerpt(value));
  const double result = value.get<double>();
  if (!std::isfinite(result)) fail(key, "must be finite");
  return result;
}

double JsonReader::number_or(const std::string& key, double fallback) { return has(key) ? number(key) : fallback; }

int JsonReader::integer_or(const std::string& key, int fallback) {
  if (!has(key)) return fallback;
  const auto& value = raw(key);
  if (!value.is_number_integer()) fail(key, "expected an integer, got " + json_excerpt(value));
  // get<int>() would wrap silently (max_iterations overflow).
  if (value.is_number_unsigned()
          ? value.get<std::uint64_t>() > static_cast<std::uint64_t>(std::numeric_limits<int>::max())
          : (value.get<std::int64_t>() > std::numeric_limits<int>::max() ||
             value.get<std::int64_t>() < std::numeric_limits<int>::min()))
    fail(key, "integer " + json_excerpt(value) + " is out of range");
  return value.get<int>();
}

std::string JsonReader::text(const std::string& key) {
  const auto& value = raw(key);
  if (!value.is_string()) fail(key, "expected a string, got " + json_excerpt(value));
  return value.get<std::string>();
}

std::string JsonReader::text_or(const std::string& key, const std::string& fallback) {
  return has(key) ? text(key) : fallback;
}

bool JsonReader::boolean_or(const std::string& key, bool fallback) {
  if (!has(key)) return fallback;
  const auto& value = raw(key);
  if (!value.is_boolean()) fail(key, "expected true or false, got " + json_excerpt(value));
  return value.get<bool>();
}

JsonReader JsonReader::object(const std::string& key) {
  const auto& value = raw(key);
  if (!value.is_object()) fail(key, "expected a JSON object {...}");
  return JsonReader(value, field(key));
}

void JsonReader::finish() const {
  for (const auto& item : object_.items())
    if (!used_.count(item.key()))
      fail(item.key(), "unknown key; remove it or check its spelling (see docs/study_format.md)");
}

}  // namespace demfit::identify::detail
