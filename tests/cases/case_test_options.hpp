#pragma once
// Case-run options shared by the case tests: fills and results cached inside the build tree, so
// tests never touch the user's cache and a clean build starts cold.
#include <string>

#include "demfit/cases/case_runner.hpp"

namespace demfit::cases::test {

inline CaseRunOptions test_options() {
  CaseRunOptions options;
  options.cache_dir = std::string(DEMFIT_BINARY_DIR) + "/test_cache";
  return options;
}

}  // namespace demfit::cases::test
