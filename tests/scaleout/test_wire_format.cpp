#include <catch2/catch.hpp>

#include <cmath>
#include <cstring>
#include <limits>

#include "demfit/scaleout/wire_format.hpp"

using namespace demfit;

namespace {
bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }
}  // namespace

TEST_CASE("Parameter sets survive the trip between ranks bit for bit", "[scaleout]") {
  const identify::ParameterSet sent{{"normk", 0.875046},
                                    {"sheark", 1.0 / 3.0},
                                    {"tiny", 4.9e-324},
                                    {"pi", M_PI},
                                    {"negative", -std::nextafter(1.0, 2.0)}};
  const identify::ParameterSet received = scaleout::decode_parameters(scaleout::encode_parameters(sent));
  REQUIRE(received.size() == sent.size());
  for (const auto& [name, value] : sent) CHECK(same_bits(received.at(name), value));
}

TEST_CASE("Outcomes keep their curves exactly and their error text", "[scaleout]") {
  identify::EvaluationOutcome sent;
  sent.ok = true;
  sent.wall_seconds = 1.25;
  identify::Curve& curve = sent.curves["pressure_volume"];
  curve.x_label = "volume_cm3";
  curve.y_label = "pressure_MPa";
  for (int i = 0; i < 50; ++i) {
    curve.x.push_back(std::exp(0.1 * i) / 7.0);
    curve.y.push_back(std::sin(0.3 * i) * 1e-7);
  }
  const identify::EvaluationOutcome received = scaleout::decode_outcome(scaleout::encode_outcome(sent));
  REQUIRE(received.ok);
  const identify::Curve& back = received.curves.at("pressure_volume");
  CHECK(back.x_label == "volume_cm3");
  CHECK(back.y_label == "pressure_MPa");
  REQUIRE(back.x.size() == curve.x.size());
  for (std::size_t i = 0; i < curve.x.size(); ++i) {
    CHECK(same_bits(back.x[i], curve.x[i]));
    CHECK(same_bits(back.y[i], curve.y[i]));
  }

  identify::EvaluationOutcome failed;
  failed.error = "time step 2e-05 s above the stable limit 1e-05 s";
  const identify::EvaluationOutcome failed_back = scaleout::decode_outcome(scaleout::encode_outcome(failed));
  CHECK_FALSE(failed_back.ok);
  CHECK(failed_back.error == failed.error);
}

TEST_CASE("A job keeps its experiment index and its parameters bit for bit", "[scaleout]") {
  const identify::EvaluationJob sent{3, {{"frics", 0.561}, {"fricr", 1.0 / 3.0}}};
  const identify::EvaluationJob received = scaleout::decode_job(scaleout::encode_job(sent));
  CHECK(received.experiment == 3);
  REQUIRE(received.parameters.size() == 2);
  for (const auto& [name, value] : sent.parameters) CHECK(same_bits(received.parameters.at(name), value));
}
