// report.html of a diagnosis: the verdict, the candidate table and the plots, written beside report.md.
#include <catch2/catch.hpp>

#include <fstream>
#include <iterator>

#include "demfit/diagnose/analytic_effects_model.hpp"
#include "demfit/diagnose/report.hpp"
#include "demfit/diagnose/workflow.hpp"
#include "demfit/identify/gnuplot.hpp"
#include "demfit/identify/report_html.hpp"

using namespace demfit;
using namespace demfit::diagnose;

TEST_CASE("The diagnosis page shows the verdict, then the candidate table, then each target's plot embedded") {
  identify::ParameterSet truth = {{"amplitude", 1.0}, {"rate", 3.0}, {"slope", 0.5}, {"stiffening_coefficient", 1.5}};
  const AnalyticEffectsModel model(101);
  Diagnosis d = run_diagnosis(analytic_effects_study(truth, 21, 0.01, 101), model, analytic_effect_candidates(),
                              DiagnoseOptions{});
  // A hostile target name stays text in the page.
  d.targets.at(0).name = "<script>alert(1)</script>";
  const auto out = std::filesystem::path(DEMFIT_BINARY_DIR) / "test_output" / "diagnose" / "html";
  std::filesystem::remove_all(out);
  std::filesystem::create_directories(out);
  write_diagnosis(d, out, true);
  std::ifstream in(out / "report.html", std::ios::binary);
  const std::string page{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  REQUIRE(d.chosen >= 0);
  const auto verdict = page.find("<h2>Verdict: " + identify::html_escape(verdict_text(d.verdict)) + " (" +
                                 d.refits[static_cast<std::size_t>(d.chosen)].effect + ")</h2>");
  REQUIRE(verdict != std::string::npos);
  const auto candidates = page.find("<h2>Candidates</h2>", verdict);
  REQUIRE(candidates != std::string::npos);
  auto row = candidates;
  for (const auto& r : d.refits) {
    row = page.find("<td>base + " + r.effect + "</td>", row);
    CHECK(row != std::string::npos);
  }
  CHECK(page.find("<script>") == std::string::npos);
  CHECK(page.find("&lt;script&gt;alert(1)&lt;/script&gt;") != std::string::npos);
  const auto plots = page.find("<h2>Plots</h2>", candidates);
  REQUIRE(plots != std::string::npos);
  const auto full = page.find("<h2>Full report</h2>", plots);
  REQUIRE(full != std::string::npos);
  if (identify::gnuplot_available()) {
    const auto picture = page.find("<img alt=\"&lt;script&gt;alert(1)&lt;/script&gt;: target", plots);
    CHECK(picture != std::string::npos);
    CHECK(picture < full);
  }
}
