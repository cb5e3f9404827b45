#pragma once
// Shared by the case tests: case-run options with fills and results cached inside the build tree,
// so tests never touch the user's cache and a clean build starts cold; a case document's refusal.
#include <exception>
#include <string>

#include <nlohmann/json.hpp>

#include "demfit/cases/case_runner.hpp"
#include "demfit/cases/case_spec.hpp"

namespace demfit::cases::test {

inline CaseRunOptions test_options() {
  CaseRunOptions options;
  options.cache_dir = std::string(DEMFIT_BINARY_DIR) + "/test_cache";
  return options;
}

// The message with which parse_case refuses `document` ("" if it is accepted).
inline std::string case_refusal(const nlohmann::json& document) {
  try {
    parse_case(document);
  } catch (const std::exception& e) { return e.what(); }
  return "";
}

}  // namespace demfit::cases::test
