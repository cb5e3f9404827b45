#pragma once
// Internal: strict reading of a JSON object. Every accessor names the full field path in its
// error ("study: variables[1].lower: expected a number"), and finish() rejects unknown keys.
#include <set>
#include <stdexcept>
#include <string>

#include <nlohmann/json.hpp>

namespace demfit::identify::detail {

class JsonReader {
 public:
  JsonReader(const nlohmann::json& object, std::string path);

  bool has(const std::string& key) const { return object_.contains(key); }
  const nlohmann::json& raw(const std::string& key);  // marks the key as used; must exist
  double number(const std::string& key);
  double number_or(const std::string& key, double fallback);
  int integer_or(const std::string& key, int fallback);
  std::string text(const std::string& key);
  std::string text_or(const std::string& key, const std::string& fallback);
  bool boolean_or(const std::string& key, bool fallback);
  JsonReader object(const std::string& key);  // nested object; must exist
  std::string field(const std::string& key) const { return path_.empty() ? key : path_ + "." + key; }
  // Throws on the first key that no accessor asked for (unknown keys are errors).
  void finish() const;
  [[noreturn]] void fail(const std::string& key, const std::string& problem) const;

 private:
  const nlohmann::json& object_;
  std::string path_;
  std::set<std::string> used_;
};

}  // namespace demfit::identify::detail
