#include "demfit/identify/lsdyna_export.hpp"

#include <cmath>
#include <cstdio>
#include <iterator>
#include <sstream>
#include <stdexcept>
#include <utility>
#include <vector>

#include "demfit/identify/safe_output.hpp"

namespace demfit::identify {
namespace {

constexpr int kFieldWidth = 10;

// The fields demfit writes, per card, as "KEYWORD FIELD" (the form of
// ParameterDescriptor::lsdyna_field); nullptr = left blank (LS-DYNA's default). Which model
// parameter fills a field is the model's fact (its descriptors), not this file's.
constexpr const char* kControlCard1[] = {"*CONTROL_DISCRETE_ELEMENT NDAMP", "*CONTROL_DISCRETE_ELEMENT TDAMP",
                                         "*CONTROL_DISCRETE_ELEMENT FRICS", "*CONTROL_DISCRETE_ELEMENT FRICR",
                                         "*CONTROL_DISCRETE_ELEMENT NORMK", "*CONTROL_DISCRETE_ELEMENT SHEARK"};
constexpr const char* kControlCard3[] = {nullptr, nullptr, nullptr, "*CONTROL_DISCRETE_ELEMENT FRICD",
                                         "*CONTROL_DISCRETE_ELEMENT DC"};
constexpr const char* kCouplingCard2[] = {"*DEFINE_DE_TO_SURFACE_COUPLING FRICS",
                                          "*DEFINE_DE_TO_SURFACE_COUPLING FRICD",
                                          "*DEFINE_DE_TO_SURFACE_COUPLING DAMP"};
constexpr const char* kWallSfp = "*DEFINE_DE_TO_SURFACE_COUPLING SFP";
constexpr const char* kFrics = "*CONTROL_DISCRETE_ELEMENT FRICS";
constexpr const char* kFricd = "*CONTROL_DISCRETE_ELEMENT FRICD";

// The descriptor whose LS-DYNA field is `field` (its text may add a remark after a blank).
const ParameterDescriptor* descriptor_of(const std::vector<ParameterDescriptor>& model, const std::string& field) {
  for (const ParameterDescriptor& d : model)
    if (d.lsdyna_field == field || d.lsdyna_field.rfind(field + " ", 0) == 0) return &d;
  return nullptr;
}

// The value a field carries: the given value of its parameter, else the parameter's default;
// NaN when the model has no parameter for the field. FRICD without a value is FRICS (LS-DYNA).
double field_value_of(const char* field, const ParameterSet& given, const std::vector<ParameterDescriptor>& model) {
  if (!field) return NAN;
  const ParameterDescriptor* d = descriptor_of(model, field);
  if (!d) return NAN;
  const auto it = given.find(d->name);
  const double value = it != given.end() ? it->second : d->default_value;
  if (std::isnan(value) && std::string(field) == kFricd) return field_value_of(kFrics, given, model);
  return value;
}

std::string shorten_exponent(std::string text) {
  const auto e = text.find('e');
  if (e == std::string::npos) return text;
  std::string mantissa = text.substr(0, e), exponent = text.substr(e + 1);
  std::string sign;
  if (!exponent.empty() && (exponent[0] == '+' || exponent[0] == '-')) {
    if (exponent[0] == '-') sign = "-";
    exponent.erase(0, 1);
  }
  while (exponent.size() > 1 && exponent[0] == '0') exponent.erase(0, 1);
  return mantissa + "e" + sign + exponent;
}

// Effect parameters the model declares without an LS-DYNA field (its descriptors: off value
// set, lsdyna_field empty). LS-DYNA's DES contact has no equivalent of these (its CAP liquid
// bridge is a different cohesion model), so a study that identified one gets a warning comment
// instead of a silently dropped value.
std::string effect_warnings(const ParameterSet& given, const std::vector<ParameterDescriptor>& model_parameters) {
  std::string text;
  for (const ParameterDescriptor& d : model_parameters) {
    if (!d.off_value || !d.lsdyna_field.empty()) continue;
    const std::string& name = d.name;
    const double off_value = *d.off_value;
    const auto it = given.find(name);
    if (it == given.end() || it->second == off_value) continue;
    char line[160];
    std::snprintf(line, sizeof line, "$ WARNING: %s = %.6g has no LS-DYNA DES field; not exported (off value %g)\n",
                  name.c_str(), it->second, off_value);
    text += line;
  }
  return text;
}

// One comment line: control characters (a newline would start a keyword line) become blanks.
std::string comment_line(const std::string& text) {
  std::string line = "$ ";
  for (char c : text) line += (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) ? ' ' : c;
  return line + "\n";
}

std::string blank() { return std::string(kFieldWidth, ' '); }

std::string card(const std::vector<std::string>& fields) {
  std::string line;
  for (const auto& f : fields) line += f;
  return line + "\n";
}

// One card of `fields` (blank where the model has no parameter), trailing blanks kept as LS-DYNA
// reads them: as defaults.
template <std::size_t N>
std::string card_of(const char* const (&fields)[N], const ParameterSet& given,
                    const std::vector<ParameterDescriptor>& model) {
  std::vector<std::string> texts;
  for (const char* field : fields) {
    const double value = field_value_of(field, given, model);
    texts.push_back(std::isnan(value) ? blank() : lsdyna_field(value));
  }
  return card(texts);
}

std::vector<std::string> data_lines_after(const std::string& text, const std::string& keyword) {
  std::istringstream in(text);
  std::string line;
  std::vector<std::string> lines;
  bool inside = false;
  while (std::getline(in, line)) {
    if (!line.empty() && line[0] == '*') {
      if (inside) break;
      inside = line.rfind(keyword, 0) == 0 && line.size() >= keyword.size();
      continue;
    }
    if (inside && !line.empty() && line[0] != '$') lines.push_back(line);
  }
  return lines;
}

double field_value(const std::string& line, int index, double fallback) {
  if (static_cast<int>(line.size()) <= index * kFieldWidth) return fallback;
  const std::string text = line.substr(index * kFieldWidth, kFieldWidth);
  if (text.find_first_not_of(' ') == std::string::npos) return fallback;
  return std::stod(text);
}

}  // namespace

std::string lsdyna_field(double value) {
  if (!std::isfinite(value)) throw std::runtime_error("LS-DYNA export: a parameter value is not finite");
  for (int digits = 10; digits >= 1; --digits) {
    char buffer[48];
    std::snprintf(buffer, sizeof buffer, "%.*g", digits, value);
    std::string text = shorten_exponent(buffer);
    // Fortran reads ".0048707" as 0.0048707: dropping the leading zero buys one digit.
    if (text.rfind("0.", 0) == 0)
      text.erase(0, 1);
    else if (text.rfind("-0.", 0) == 0)
      text.erase(1, 1);
    // One leading blank keeps neighbouring fields apart for the human reader.
    if (static_cast<int>(text.size()) <= kFieldWidth - 1) return std::string(kFieldWidth - text.size(), ' ') + text;
  }
  throw std::runtime_error("LS-DYNA export: value " + std::to_string(value) + " does not fit a 10-character field");
}

// Card layouts (10-character fields, LS-DYNA Keyword User's Manual Vol. I):
//   *CONTROL_DISCRETE_ELEMENT card 1: NDAMP TDAMP FRICS FRICR NORMK SHEARK CAP MXNSC;
//     card 2: GAMMA VOL ANG GAP (unused) IGNORE NBUF PARALLEL (capillary data, blank = dry);
//     card 3: LNORM LSHEAR (unused) FRICD DC NCRB BT DT.
//   *DEFINE_DE_TO_SURFACE_COUPLING card 1: SLAVE MASTER STYPE MTYPE; card 2: FRICS FRICD DAMP BSORT ...
// Checked against the field schema of the keyword classes generated from the manual (Ansys pydyna,
// keyword_classes/auto: control_discrete_element, define_de_to_surface_coupling) on 2026-11-24.
std::string lsdyna_keywords(const ParameterSet& parameters, const std::vector<ParameterDescriptor>& model_parameters,
                            const std::string& title, const std::vector<std::string>& comments) {
  std::ostringstream out;
  out << "*KEYWORD\n" << comment_line("demfit export: " + title);
  for (const auto& c : comments) out << comment_line(c);
  out << "$ DEM contact parameters identified by demfit; other fields blank = LS-DYNA defaults.\n"
      << effect_warnings(parameters, model_parameters) << "*CONTROL_DISCRETE_ELEMENT\n"
      << "$    NDAMP     TDAMP     FRICS     FRICR     NORMK    SHEARK       CAP     MXNSC\n"
      << card_of(kControlCard1, parameters, model_parameters)
      << "$    GAMMA       VOL       ANG       GAP    unused    IGNORE      NBUF  PARALLEL\n"
      << card({blank()}) << "$    LNORM    LSHEAR    unused     FRICD        DC      NCRB        BT        DT\n"
      << card_of(kControlCard3, parameters, model_parameters) << "*DEFINE_DE_TO_SURFACE_COUPLING\n"
      << "$ SLAVE/MASTER/STYPE/MTYPE are placeholders: set them to your DES and surface sets.\n"
      << "$    SLAVE    MASTER     STYPE     MTYPE\n"
      << card({lsdyna_field(1), lsdyna_field(2), lsdyna_field(0), lsdyna_field(0)})
      << "$    FRICS     FRICD      DAMP     BSORT\n"
      << card_of(kCouplingCard2, parameters, model_parameters);
  if (const double sfp = field_value_of(kWallSfp, parameters, model_parameters); !std::isnan(sfp))
    out << "$ wall stiffness scale factor SFP used by demfit: " << lsdyna_field(sfp) << "\n";
  out << "*END\n";
  return out.str();
}

void write_lsdyna_keywords(const std::filesystem::path& path, const ParameterSet& parameters,
                           const std::vector<ParameterDescriptor>& model_parameters, const std::string& title,
                           const std::vector<std::string>& comments) {
  // Only a regular file is replaced: never a device, a link (e.g. to /dev/stdout) or a folder.
  write_user_file(path, lsdyna_keywords(parameters, model_parameters, title, comments), /*overwrite=*/true,
                  "LS-DYNA keyword file");
}

ParameterSet parse_lsdyna_keywords(const std::string& text, const std::vector<ParameterDescriptor>& model_parameters) {
  const auto control = data_lines_after(text, "*CONTROL_DISCRETE_ELEMENT");
  const auto coupling = data_lines_after(text, "*DEFINE_DE_TO_SURFACE_COUPLING");
  if (control.size() < 3 || coupling.size() < 2)
    throw std::runtime_error(
        "LS-DYNA keywords: *CONTROL_DISCRETE_ELEMENT needs 3 cards and "
        "*DEFINE_DE_TO_SURFACE_COUPLING 2 cards");
  ParameterSet p;
  auto read_card = [&](const auto& fields, const std::string& line) {
    for (std::size_t i = 0; i < std::size(fields); ++i) {
      const ParameterDescriptor* d = fields[i] ? descriptor_of(model_parameters, fields[i]) : nullptr;
      if (d) p[d->name] = field_value(line, static_cast<int>(i), d->default_value);
    }
  };
  read_card(kControlCard1, control[0]);
  read_card(kControlCard3, control[2]);
  read_card(kCouplingCard2, coupling[1]);
  // A blank FRICD is FRICS (LS-DYNA).
  const ParameterDescriptor* fricd = descriptor_of(model_parameters, kFricd);
  const ParameterDescriptor* frics = descriptor_of(model_parameters, kFrics);
  if (fricd && frics && std::isnan(p[fricd->name])) p[fricd->name] = p[frics->name];
  return p;
}

}  // namespace demfit::identify
