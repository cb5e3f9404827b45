// Strict case parsing: shipped case files load, defaults resolve, bad input names its field.
#include <catch2/catch.hpp>

#include <string>

#include "demfit/cases/case_spec.hpp"

using namespace demfit::cases;
using nlohmann::json;

namespace {
std::string message_of(const json& document) {
  try {
    parse_case(document);
  } catch (const std::exception& e) {
    return e.what();
  }
  return "";
}
}  // namespace

TEST_CASE("The shipped case files parse and their resolved JSON parses back to the same values") {
  for (const char* name : {"pellet_compression.json", "rotary_drum.json"}) {
    const json document = read_case_json(std::string(DEMFIT_SOURCE_DIR) + "/cases/" + name);
    const CaseSpec spec = parse_case(document);
    const json resolved = to_json(spec);
    CHECK(to_json(parse_case(resolved)) == resolved);
  }
}

TEST_CASE("The pellet case's bulk modulus is E / (3 (1 - 2 nu)) = 1767 MPa as in Table 1") {
  const CaseSpec spec =
      parse_case(read_case_json(std::string(DEMFIT_SOURCE_DIR) + "/cases/pellet_compression.json"));
  CHECK(spec.material.bulk_modulus() == Approx(1.06e9 / (3.0 * (1.0 - 0.8))).epsilon(1e-14));
  CHECK(std::lround(spec.material.bulk_modulus() / 1e6) == 1767);
}

TEST_CASE("Unknown keys, negative radii and wrong types are rejected with the dotted field name") {
  const json base = {{"case", "pellet_compression"}};
  json unknown = base;
  unknown["pellet"] = {{"piston_sped", 0.1}};
  CHECK(message_of(unknown).find("pellet.piston_sped") != std::string::npos);
  json negative = base;
  negative["particle"] = {{"radius", -0.001}};
  CHECK(message_of(negative).find("particle.radius") != std::string::npos);
  json wrong_type = base;
  wrong_type["contact"] = {{"normk", "big"}};
  CHECK(message_of(wrong_type).find("contact.normk") != std::string::npos);
  CHECK(message_of(json{{"case", "mixer"}}).find("case") != std::string::npos);
  CHECK(message_of(json{{"case", "rotary_drum"}, {"drum", {{"coarse_graining", "xyz"}}}})
            .find("drum.coarse_graining") != std::string::npos);
}

TEST_CASE("FRICD defaults to FRICS when the file leaves it out (LS-DYNA default)") {
  const CaseSpec spec = parse_case(json{{"case", "pellet_compression"}, {"contact", {{"frics", 0.4}}}});
  CHECK(spec.contact.fricd == 0.4);
}

TEST_CASE("Setting overrides address identified parameters by name and other fields by dotted path") {
  json document = {{"case", "rotary_drum"}};
  apply_setting(document, "normk=0.5");
  apply_setting(document, "wall_damp=0.25");
  apply_setting(document, "drum.coarse_graining=cvf");
  apply_setting(document, "drum.scale_factor=4");
  const CaseSpec spec = parse_case(document);
  CHECK(spec.contact.normk == 0.5);
  CHECK(spec.wall.damp == 0.25);
  CHECK(spec.drum.coarse_graining == CoarseGraining::cvf);
  CHECK(spec.drum.scale_factor == 4.0);
  CHECK_THROWS(apply_setting(document, "normk"));
}
