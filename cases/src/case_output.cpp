// All-or-nothing output of a case run (see case_output.hpp).
#include "demfit/cases/case_output.hpp"

#include <unistd.h>

#include <cstdio>
#include <stdexcept>

#include "demfit/cases/synthetic_noise.hpp"
#include "demfit/identify/safe_output.hpp"

namespace demfit::cases {

StagedDirectory::StagedDirectory(std::filesystem::path target) : target_(std::move(target)) {
  if (target_.filename().empty()) target_ = target_.parent_path();  // "out/" -> "out"
  std::string name = ".";  // built by appending: GCC 12 warns (-Wrestrict) on "literal" + string
  name += target_.filename().string();
  name += ".partial-";
  name += std::to_string(getpid());
  staging_ = target_.parent_path() / name;
}

StagedDirectory::~StagedDirectory() {
  if (created_ && !committed_) {
    std::error_code ignored;
    std::filesystem::remove_all(staging_, ignored);
  }
}

const std::filesystem::path& StagedDirectory::path() {
  if (!created_) {
    std::error_code error;
    if (!target_.parent_path().empty()) std::filesystem::create_directories(target_.parent_path(), error);
    std::filesystem::remove_all(staging_, error);
    if (!std::filesystem::create_directory(staging_, error)) {
      throw std::runtime_error("cannot create output folder next to '" + target_.string() + "': " + error.message());
    }
    created_ = true;
  }
  return staging_;
}

void StagedDirectory::commit() {
  path();
  std::error_code error;
  std::filesystem::remove_all(target_, error);
  std::filesystem::rename(staging_, target_, error);
  if (error) throw std::runtime_error("cannot move results to '" + target_.string() + "': " + error.message());
  committed_ = true;
}

void write_case_result(const std::filesystem::path& dir, const CaseResult& result, const nlohmann::json& resolved_case,
                       const identify::ParameterSet& parameters, const SyntheticNoise& noise) {
  std::string parameter_line = "parameters:";
  for (const auto& [name, value] : parameters) {
    char buffer[64];
    std::snprintf(buffer, sizeof buffer, " %s=%.9g", name.c_str(), value);
    parameter_line += buffer;
  }
  std::uint64_t k = 0;
  for (const auto& [name, curve] : result.curves) {
    std::vector<std::string> comments{"demfit curve '" + name + "' of case '" + resolved_case.value("case", "") + "'",
                                      parameter_line};
    identify::Curve written = curve;
    if (noise.relative > 0.0) {
      written.y = add_relative_noise(curve.y, noise.relative, noise.seed + k);
      char buffer[200];
      std::snprintf(buffer, sizeof buffer,
                    "SYNTHETIC data: simulated by demfit, plus Gaussian noise sigma = %g x max|y|, seed %llu",
                    noise.relative, static_cast<unsigned long long>(noise.seed + k));
      comments.insert(comments.begin(), buffer);
    }
    write_curve_table(dir / (name + ".csv"), curve_table(written, comments));
    ++k;
  }
  for (const auto& [name, table] : result.tables) write_curve_table(dir / (name + ".csv"), table);
  identify::write_file_atomically(dir / "case_resolved.json", resolved_case.dump(2) + '\n');
  identify::write_file_atomically(dir / "summary.txt", parameter_line + '\n' + format_summary(result));
}

std::string format_summary(const CaseResult& result, int points_per_curve) {
  std::string out;
  std::size_t width = 0;
  for (const auto& [label, value] : result.summary) width = std::max(width, label.size());
  for (const auto& [label, value] : result.summary) {
    out += "  " + label + std::string(width - label.size() + 2, ' ') + value + '\n';
  }
  for (const auto& [name, curve] : result.curves) {
    out += "\ncurve " + name + " (" + std::to_string(curve.x.size()) + " points)\n";
    char line[128];
    std::snprintf(line, sizeof line, "  %14s  %14s\n", curve.x_label.c_str(), curve.y_label.c_str());
    out += line;
    const std::size_t n = curve.x.size();
    const std::size_t shown = std::min<std::size_t>(n, static_cast<std::size_t>(points_per_curve));
    for (std::size_t i = 0; i < shown; ++i) {
      const std::size_t j = shown == 1 ? 0 : i * (n - 1) / (shown - 1);
      std::snprintf(line, sizeof line, "  %14.6g  %14.6g\n", curve.x[j], curve.y[j]);
      out += line;
    }
  }
  return out;
}

}  // namespace demfit::cases
