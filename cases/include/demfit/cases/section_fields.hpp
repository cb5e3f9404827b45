#pragma once
// A case-file section's plain fields as one table (one source of truth per fact): each
// row is the key, the member of the section's struct it fills and the rule its value obeys. The
// section's accepted keys, its strict reading and its JSON text are all derived from the table,
// so a new field is one row (plus its physics), never three edits that can drift apart.
#include <limits>
#include <span>
#include <string>
#include <variant>
#include <vector>

#include <nlohmann/json.hpp>

#include "demfit/cases/json_fields.hpp"

namespace demfit::cases {

inline constexpr double kUnbounded = std::numeric_limits<double>::infinity();

template <class Section>
struct SectionField {
  const char* key;  ///< JSON key in the section (its unit is in the struct's comment and docs)
  std::variant<double Section::*, long long Section::*, bool Section::*> member;
  Sign sign = Sign::any;     ///< numbers: sign rule (when no bounds are given)
  double low = -kUnbounded;  ///< numbers: closed bounds [low, high], used when one is finite
  double high = kUnbounded;
  long long minimum = 0;  ///< integers: smallest accepted value
};

/// The table's keys, then `extra` (the section's fields that need their own code).
template <class Section>
std::vector<std::string> section_keys(std::span<const SectionField<Section>> fields,
                                      std::vector<std::string> extra = {}) {
  std::vector<std::string> keys;
  for (const SectionField<Section>& f : fields) keys.emplace_back(f.key);
  for (std::string& k : extra) keys.push_back(std::move(k));
  return keys;
}

/// Reads every field of the table from `object` into `section` (absent keys keep its value).
template <class Section>
void read_section_fields(const nlohmann::json& object, std::string_view path,
                         std::span<const SectionField<Section>> fields, Section& section) {
  for (const SectionField<Section>& f : fields) {
    if (const auto* number = std::get_if<double Section::*>(&f.member)) {
      double& value = section.**number;
      const bool bounded = f.low > -kUnbounded || f.high < kUnbounded;
      value = bounded ? read_bounded(object, path, f.key, value, f.low, f.high)
                      : read_number(object, path, f.key, value, f.sign);
    } else if (const auto* integer = std::get_if<long long Section::*>(&f.member)) {
      section.** integer = read_integer(object, path, f.key, section.**integer, f.minimum);
    } else {
      bool& flag = section.*std::get<bool Section::*>(f.member);
      flag = read_bool(object, path, f.key, flag);
    }
  }
}

/// Writes every field of the table into the JSON object `out`.
template <class Section>
void write_section_fields(nlohmann::json& out, std::span<const SectionField<Section>> fields, const Section& section) {
  for (const SectionField<Section>& f : fields)
    std::visit([&](auto member) { out[f.key] = section.*member; }, f.member);
}

}  // namespace demfit::cases
