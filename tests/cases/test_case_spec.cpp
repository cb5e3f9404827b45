// Strict case parsing: shipped case files load, defaults resolve, bad input names its field.
#include <catch2/catch.hpp>

#include <string>

#include "demfit/cases/case_registry.hpp"
#include "demfit/cases/case_spec.hpp"

using namespace demfit::cases;
using nlohmann::json;

namespace {
std::string message_of(const json& document) {
  try {
    parse_case(document);
  } catch (const std::exception& e) { return e.what(); }
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
  const CaseSpec spec = parse_case(read_case_json(std::string(DEMFIT_SOURCE_DIR) + "/cases/pellet_compression.json"));
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
  CHECK(
      message_of(json{{"case", "rotary_drum"}, {"drum", {{"coarse_graining", "xyz"}}}}).find("drum.coarse_graining") !=
      std::string::npos);
}

TEST_CASE("numerics.reorder_particles is off unless the case asks, and only a case that asks gets other cache keys") {
  const CaseSpec plain = parse_case(json{{"case", "rotary_drum"}});
  CHECK_FALSE(plain.numerics.reorder_particles);
  CHECK_FALSE(to_key_json(plain).contains("numerics"));  // fills and results cached before stay valid
  const CaseSpec reordered = parse_case(json{{"case", "rotary_drum"}, {"numerics", {{"reorder_particles", true}}}});
  CHECK(reordered.numerics.reorder_particles);
  CHECK(to_key_json(reordered) != to_key_json(plain));
  CHECK(to_json(parse_case(to_json(reordered))) == to_json(reordered));
  CHECK(message_of(json{{"case", "rotary_drum"}, {"numerics", {{"reorder", true}}}}).find("numerics.reorder") !=
        std::string::npos);
  CHECK(message_of(json{{"case", "rotary_drum"}, {"numerics", {{"reorder_particles", "yes"}}}})
            .find("numerics.reorder_particles") != std::string::npos);
}

TEST_CASE("numerics.pair_load_order keeps the published order unless the case asks, with its own cache key") {
  const CaseSpec plain = parse_case(json{{"case", "rotary_drum"}});
  CHECK(plain.numerics.pair_load_order == demfit::dem_core::PairLoadOrder::own_row_first);
  const CaseSpec lean =
      parse_case(json{{"case", "rotary_drum"}, {"numerics", {{"pair_load_order", "ascending_first_member"}}}});
  CHECK(lean.numerics.pair_load_order == demfit::dem_core::PairLoadOrder::ascending_first_member);
  CHECK(to_key_json(lean) != to_key_json(plain));  // another round-off realisation: other fills
  CHECK_FALSE(to_key_json(lean)["numerics"].contains("reorder_particles"));
  CHECK(to_json(parse_case(to_json(lean))) == to_json(lean));
  const std::string message = message_of(json{{"case", "rotary_drum"}, {"numerics", {{"pair_load_order", "fastest"}}}});
  CHECK(message.find("numerics.pair_load_order") != std::string::npos);
  CHECK(message.find("ascending_first_member") != std::string::npos);
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

TEST_CASE("Every case kind has one registry row, found by its case-file name, and an unknown kind names them all") {
  const auto& table = case_kind_table();
  for (std::size_t i = 0; i < table.size(); ++i) {
    CHECK(&case_kind_row(table[i].kind) == &table[i]);
    REQUIRE(find_case_kind(table[i].name) == &table[i]);
    if (table[i].kind == CaseKind::mesh_container)  // no default geometry: the error names its section
      CHECK(message_of({{"case", table[i].name}}).find("'mesh_container' is missing") == 0);
    else
      CHECK(parse_case({{"case", table[i].name}}).kind == table[i].kind);
    for (std::size_t j = 0; j < table.size(); ++j)
      if (j != i) CHECK(std::string(table[i].section) != table[j].section);
  }
  CHECK(find_case_kind("ball_mill") == nullptr);
  const std::string message = message_of({{"case", "ball_mill"}});
  for (const auto& row : table) CHECK(message.find(std::string("\"") + row.name + "\"") != std::string::npos);
  CHECK(message.find("ball_mill") != std::string::npos);
}

TEST_CASE("A case file carrying another kind's section is refused naming the section") {
  CHECK(message_of({{"case", "pellet_compression"}, {"drum", json::object()}}) ==
        "'drum' is not allowed in a pellet_compression case");
  CHECK(message_of({{"case", "rotary_drum"}, {"pellet", json::object()}}) ==
        "'pellet' is not allowed in a rotary_drum case");
}

TEST_CASE(
    "The curves a case declares follow its options: the pellet cycle with unload, the image surface with drum.image") {
  auto names = [](const CaseSpec& spec) {
    std::vector<std::string> out;
    for (const auto& c : produced_curves(spec)) out.push_back(c.name);
    return out;
  };
  json pellet = {{"case", "pellet_compression"}};
  CHECK(names(parse_case(pellet)) ==
        std::vector<std::string>{"pressure_volume", "bottom_force_volume", "quasi_static_check"});
  pellet["pellet"] = {{"unload", true}};
  CHECK(names(parse_case(pellet)) == std::vector<std::string>{"pressure_volume", "bottom_force_volume",
                                                              "pressure_volume_cycle", "quasi_static_check"});
  json drum = {{"case", "rotary_drum"}};
  CHECK(names(parse_case(drum)) == std::vector<std::string>{"torque", "free_surface"});
  drum["drum"] = {{"image", {{"pixels", 200}}}};
  CHECK(names(parse_case(drum)) == std::vector<std::string>{"torque", "free_surface", "free_surface_image"});
  CHECK(case_curve(CaseKind::rotary_drum, "torque").y_label == "torque_Nm");
  CHECK_THROWS_AS(case_curve(CaseKind::rotary_drum, "pressure_volume"), std::logic_error);
}
