#pragma once
// Strict reading of case JSON: every object lists the keys it accepts, anything else is an
// error naming the full dotted path of the offending field (DESIGN "parse input once, at the
// door"). All errors are std::runtime_error with a one-line message naming the field and the fix.
#include <initializer_list>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

namespace demfit::cases {

// Throws unless `object` is a JSON object whose keys are all in `allowed`.
// `path` is the dotted location of `object` ("" for the root), used in messages.
void require_known_keys(const nlohmann::json& object, std::string_view path,
                        std::initializer_list<std::string_view> allowed);
void require_known_keys(const nlohmann::json& object, std::string_view path, const std::vector<std::string>& allowed);

// Dotted child path: join_path("piston", "speed") == "piston.speed"; join_path("", "x") == "x".
std::string join_path(std::string_view path, std::string_view key);

// Returns the sub-object `key` of `object` (an empty object when absent); throws if not an object.
const nlohmann::json& child_object(const nlohmann::json& object, std::string_view path, const char* key);

enum class Sign { any, positive, non_negative };

// Reads a finite number, `fallback` when the key is absent. Rejects strings, NaN and values that
// violate `sign`, naming the field.
double read_number(const nlohmann::json& object, std::string_view path, const char* key, double fallback,
                   Sign sign = Sign::any);

// Reads an integer >= `minimum` (`fallback` when absent).
long long read_integer(const nlohmann::json& object, std::string_view path, const char* key, long long fallback,
                       long long minimum);

bool read_bool(const nlohmann::json& object, std::string_view path, const char* key, bool fallback);

std::string read_string(const nlohmann::json& object, std::string_view path, const char* key,
                        const std::string& fallback);

// Reads a number that must lie in [low, high].
double read_bounded(const nlohmann::json& object, std::string_view path, const char* key, double fallback, double low,
                    double high);

}  // namespace demfit::cases
