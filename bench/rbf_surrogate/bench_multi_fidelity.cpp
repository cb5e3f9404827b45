// Would cheap runs help? Multi-fidelity kriging (multi_fidelity.hpp) against kriging of the fine
// runs alone, on the evaluations of two studies of one problem at two resolutions (e.g. the
// GranuDrum calibration at coarse-graining factors s = 3 and s = 1.5: same variables, same
// objective, runs 16 times cheaper at s = 3).
//
//   bench_rbf_multi_fidelity COARSE.csv FINE.csv VAR:LOWER:UPPER [VAR:LOWER:UPPER ...]
//
// The files are a study's evaluations.csv (columns iteration, point, kind, status, objective, the
// variables; rows with status other than "ok" are skipped). Both models see log10(objective) (the
// objective spans decades) in unit coordinates of the given bounds. Printed:
//  - leave-one-out over the fine runs: each fine run predicted by kriging of the other fine runs
//    and by the two-level model (all coarse runs + the other fine runs); RMS of the log10 errors;
//  - the same with only the first k fine runs known (the study's order: initial design first),
//    predicting the remaining fine runs, for k = 4, 6, 8, …;
//  - the scale ρ of the coarse level and the coarse level's own error on the fine runs.
#include "demfit/rbf_surrogate/multi_fidelity.hpp"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

using namespace demfit::rbf_surrogate;

namespace {

struct Bound {
  std::string name;
  double lower, upper;
};

std::vector<std::string> split_csv_line(const std::string& line) {
  std::vector<std::string> cells;
  std::string cell;
  bool quoted = false;
  for (char c : line) {
    if (c == '"')
      quoted = !quoted;
    else if (c == ',' && !quoted)
      cells.push_back(cell), cell.clear();
    else
      cell += c;
  }
  cells.push_back(cell);
  return cells;
}

// The successful runs of an evaluations.csv: unit points and log10 objectives.
FidelityLevel read_runs(const std::string& path, const std::vector<Bound>& bounds) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot read " + path);
  std::string line;
  std::getline(in, line);
  const std::vector<std::string> header = split_csv_line(line);
  auto column = [&](const std::string& name) {
    for (std::size_t c = 0; c < header.size(); ++c)
      if (header[c] == name) return c;
    throw std::runtime_error(path + ": no column " + name);
  };
  const std::size_t status = column("status"), objective = column("objective");
  std::vector<std::size_t> variables;
  for (const Bound& b : bounds) variables.push_back(column(b.name));
  std::vector<std::vector<double>> rows;
  std::vector<double> values;
  while (std::getline(in, line)) {
    const std::vector<std::string> cells = split_csv_line(line);
    if (cells.size() < header.size() || cells[status] != "ok") continue;
    std::vector<double> unit;
    for (std::size_t v = 0; v < bounds.size(); ++v)
      unit.push_back((std::stod(cells[variables[v]]) - bounds[v].lower) / (bounds[v].upper - bounds[v].lower));
    rows.push_back(unit);
    values.push_back(std::log10(std::stod(cells[objective])));
  }
  FidelityLevel level;
  level.points.resize(static_cast<Eigen::Index>(rows.size()), static_cast<Eigen::Index>(bounds.size()));
  level.values.resize(static_cast<Eigen::Index>(rows.size()));
  for (std::size_t r = 0; r < rows.size(); ++r) {
    for (std::size_t v = 0; v < bounds.size(); ++v)
      level.points(static_cast<Eigen::Index>(r), static_cast<Eigen::Index>(v)) = rows[r][v];
    level.values(static_cast<Eigen::Index>(r)) = values[r];
  }
  return level;
}

FidelityLevel subset(const FidelityLevel& level, const std::vector<Eigen::Index>& rows) {
  FidelityLevel out;
  out.points.resize(static_cast<Eigen::Index>(rows.size()), level.points.cols());
  out.values.resize(static_cast<Eigen::Index>(rows.size()));
  for (std::size_t r = 0; r < rows.size(); ++r) {
    out.points.row(static_cast<Eigen::Index>(r)) = level.points.row(rows[r]);
    out.values(static_cast<Eigen::Index>(r)) = level.values(rows[r]);
  }
  return out;
}

struct Errors {
  double single = 0.0, two_level = 0.0, coarse_only = 0.0;
  int count = 0;
  double scale_sum = 0.0;
};

// Fits both models on the fine rows `known` and adds their squared errors at the rows `predicted`.
void add_errors(const FidelityLevel& coarse, const FidelityLevel& fine, const std::vector<Eigen::Index>& known,
                const std::vector<Eigen::Index>& predicted, const MultiFidelityOptions& options, Errors& e) {
  const FidelityLevel fine_known = subset(fine, known);
  const KrigingModel single = KrigingModel::fit(fine_known.points, fine_known.values, options.kriging);
  const MultiFidelityModel two = MultiFidelityModel::fit({coarse, fine_known}, options);
  for (Eigen::Index r : predicted) {
    const VectorXd x = fine.points.row(r).transpose();
    double coarse_mean = 0.0, sd = 0.0;
    two.predict_level(0, x, coarse_mean, sd);
    e.single += std::pow(single.mean(x) - fine.values(r), 2);
    e.two_level += std::pow(two.mean(x) - fine.values(r), 2);
    e.coarse_only += std::pow(coarse_mean - fine.values(r), 2);
    ++e.count;
  }
  e.scale_sum += two.scale(1);
}

void print_row(const char* label, const Errors& e, int fits) {
  std::printf("%-34s %4d  %10.3f  %10.3f  %10.3f  %6.2f\n", label, e.count, std::sqrt(e.single / e.count),
              std::sqrt(e.two_level / e.count), std::sqrt(e.coarse_only / e.count), e.scale_sum / fits);
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 4) {
    std::fprintf(stderr,
                 "usage: bench_rbf_multi_fidelity COARSE_evaluations.csv FINE_evaluations.csv VAR:LOWER:UPPER ...\n"
                 "  (bounds in the variables' own units; log10 of the objective is modelled)\n");
    return 2;
  }
  try {
    std::vector<Bound> bounds;
    for (int a = 3; a < argc; ++a) {
      std::istringstream text(argv[a]);
      Bound b;
      std::string lower, upper;
      if (!std::getline(text, b.name, ':') || !std::getline(text, lower, ':') || !std::getline(text, upper))
        throw std::runtime_error(std::string("bad bound ") + argv[a] + "; write NAME:LOWER:UPPER");
      b.lower = std::stod(lower);
      b.upper = std::stod(upper);
      bounds.push_back(b);
    }
    const FidelityLevel coarse = read_runs(argv[1], bounds), fine = read_runs(argv[2], bounds);
    MultiFidelityOptions options;
    options.kriging.estimate_noise = true;  // DEM objectives scatter from fill to fill
    std::printf(
        "coarse runs %ld (%s), fine runs %ld (%s); model: log10(objective), Matern-5/2 kriging, nugget "
        "estimated\n",
        static_cast<long>(coarse.values.size()), argv[1], static_cast<long>(fine.values.size()), argv[2]);
    std::printf("%-34s %4s  %10s  %10s  %10s  %6s\n", "fine runs known", "pred", "fine only", "two-level",
                "coarse only", "rho");
    const auto n = static_cast<Eigen::Index>(fine.values.size());
    Errors loo;
    for (Eigen::Index left = 0; left < n; ++left) {
      std::vector<Eigen::Index> known;
      for (Eigen::Index r = 0; r < n; ++r)
        if (r != left) known.push_back(r);
      add_errors(coarse, fine, known, {left}, options, loo);
    }
    print_row("all but one (leave-one-out)", loo, static_cast<int>(n));
    for (Eigen::Index k = 4; k + 2 <= n; k += 2) {
      std::vector<Eigen::Index> known, predicted;
      for (Eigen::Index r = 0; r < n; ++r) (r < k ? known : predicted).push_back(r);
      Errors e;
      add_errors(coarse, fine, known, predicted, options, e);
      char label[64];
      std::snprintf(label, sizeof label, "first %ld, predicting the rest", static_cast<long>(k));
      print_row(label, e, 1);
    }
    std::printf("(RMS of log10 errors: 0.1 = a factor 1.26 on the objective, 0.3 = a factor 2)\n");
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_rbf_multi_fidelity: %s\n", e.what());
    return 1;
  }
  return 0;
}
