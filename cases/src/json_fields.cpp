// Strict JSON field access for case files (see json_fields.hpp).
#include "demfit/cases/json_fields.hpp"

#include <cmath>
#include <stdexcept>

namespace demfit::cases {

std::string join_path(std::string_view path, std::string_view key) {
  if (path.empty()) return std::string(key);
  return std::string(path) + "." + std::string(key);
}

void require_known_keys(const nlohmann::json& object, std::string_view path,
                        std::initializer_list<std::string_view> allowed) {
  require_known_keys(object, path, std::vector<std::string>(allowed.begin(), allowed.end()));
}

void require_known_keys(const nlohmann::json& object, std::string_view path, const std::vector<std::string>& allowed) {
  if (!object.is_object()) {
    throw std::runtime_error("'" + (path.empty() ? std::string("<root>") : std::string(path)) +
                             "' must be a JSON object");
  }
  for (const auto& item : object.items()) {
    bool known = false;
    for (const std::string& name : allowed) known = known || item.key() == name;
    if (!known) {
      std::string list;
      for (const std::string& name : allowed) list += (list.empty() ? "" : ", ") + name;
      throw std::runtime_error("unknown key '" + join_path(path, item.key()) + "' (allowed here: " + list + ")");
    }
  }
}

const nlohmann::json& child_object(const nlohmann::json& object, std::string_view path, const char* key) {
  static const nlohmann::json empty = nlohmann::json::object();
  auto it = object.find(key);
  if (it == object.end()) return empty;
  if (!it->is_object()) { throw std::runtime_error("'" + join_path(path, key) + "' must be a JSON object {...}"); }
  return *it;
}

double read_number(const nlohmann::json& object, std::string_view path, const char* key, double fallback, Sign sign) {
  auto it = object.find(key);
  if (it == object.end()) return fallback;
  const std::string name = join_path(path, key);
  if (!it->is_number()) throw std::runtime_error("'" + name + "' must be a number");
  const double value = it->get<double>();
  if (!std::isfinite(value)) throw std::runtime_error("'" + name + "' must be finite");
  if (sign == Sign::positive && !(value > 0.0)) {
    throw std::runtime_error("'" + name + "' must be > 0 (got " + it->dump() + ")");
  }
  if (sign == Sign::non_negative && value < 0.0) {
    throw std::runtime_error("'" + name + "' must be >= 0 (got " + it->dump() + ")");
  }
  return value;
}

long long read_integer(const nlohmann::json& object, std::string_view path, const char* key, long long fallback,
                       long long minimum) {
  auto it = object.find(key);
  if (it == object.end()) return fallback;
  const std::string name = join_path(path, key);
  if (!it->is_number_integer()) throw std::runtime_error("'" + name + "' must be an integer");
  const long long value = it->get<long long>();
  if (value < minimum) {
    throw std::runtime_error("'" + name + "' must be >= " + std::to_string(minimum) + " (got " + std::to_string(value) +
                             ")");
  }
  return value;
}

bool read_bool(const nlohmann::json& object, std::string_view path, const char* key, bool fallback) {
  auto it = object.find(key);
  if (it == object.end()) return fallback;
  if (!it->is_boolean()) { throw std::runtime_error("'" + join_path(path, key) + "' must be true or false"); }
  return it->get<bool>();
}

std::string read_string(const nlohmann::json& object, std::string_view path, const char* key,
                        const std::string& fallback) {
  auto it = object.find(key);
  if (it == object.end()) return fallback;
  if (!it->is_string()) throw std::runtime_error("'" + join_path(path, key) + "' must be a string");
  return it->get<std::string>();
}

double read_bounded(const nlohmann::json& object, std::string_view path, const char* key, double fallback, double low,
                    double high) {
  const double value = read_number(object, path, key, fallback);
  if (value < low || value > high) {
    throw std::runtime_error("'" + join_path(path, key) + "' must lie in [" + std::to_string(low) + ", " +
                             std::to_string(high) + "] (got " + std::to_string(value) + ")");
  }
  return value;
}

}  // namespace demfit::cases
