#pragma once
// What a study simulates, as resolved JSON (for DEM cases: the case with every default filled in,
// not the case file's path), kept in the study store so that --resume refuses a changed model and
// names the field that changed.
#include <string>

#include <nlohmann/json.hpp>

namespace demfit::identify {

// "" when equal; else a one-line description of the first difference, e.g.
// "pellet.count: was 1450, now 1500".
std::string first_difference(const nlohmann::json& before, const nlohmann::json& now, const std::string& path = "");

}  // namespace demfit::identify
