// Candidate effects as data; see effect.hpp.
#include "demfit/diagnose/effect.hpp"

#include <set>
#include <stdexcept>

namespace demfit::diagnose {

void validate_candidates(const std::vector<EffectCandidate>& candidates) {
  std::set<std::string> names;
  for (const auto& c : candidates) {
    if (c.name.empty()) throw std::runtime_error("effect candidate: name is empty; give every candidate a name");
    if (!names.insert(c.name).second)
      throw std::runtime_error("effect candidate '" + c.name + "': duplicate name; names must be unique");
    if (c.parameters.empty())
      throw std::runtime_error("effect candidate '" + c.name +
                               "': parameters is empty; an effect adds at least one parameter");
    for (const auto& p : c.parameters) {
      if (!(p.lower < p.upper))
        throw std::runtime_error("effect candidate '" + c.name + "': parameter '" + p.name + "' needs lower < upper");
      if (p.off_value < p.lower || p.off_value > p.upper)
        throw std::runtime_error("effect candidate '" + c.name + "': parameter '" + p.name +
                                 "' off_value is outside [lower, upper]; widen the bounds");
    }
  }
}

std::vector<EffectCandidate> analytic_effect_candidates() {
  return {
      {"toe_shift",
       "the response starts late: base curve shifted right by s (seating, initial gap)",
       {{"toe_shift", 0.0, 0.2, 0.0, "-"}},
       {"response"}},
      {"stiffening",
       "progressive stiffening: extra term c x^2 (e.g. Hertzian-like hardening)",
       {{"stiffening_coefficient", -1.0, 2.0, 0.0, "-"}},
       {"response"}},
      {"yield_drop",
       "softening past x = 0.7: -h (x-0.7)/0.3 (plastic yield of contacts)",
       {{"yield_drop", -0.5, 0.5, 0.0, "-"}},
       {"response"}},
  };
}

std::vector<EffectCandidate> select_candidates(const std::vector<EffectCandidate>& candidates,
                                               const std::string& list) {
  std::vector<EffectCandidate> out;
  std::string token;
  auto flush = [&] {
    if (token.empty()) return;
    bool found = false;
    for (const auto& c : candidates)
      if (c.name == token) {
        out.push_back(c);
        found = true;
      }
    if (!found) {
      std::string known;
      for (const auto& c : candidates) known += (known.empty() ? "" : ", ") + c.name;
      throw std::runtime_error("--effects: unknown effect '" + token +
                               "'; known: " + (known.empty() ? "(none)" : known));
    }
    token.clear();
  };
  for (char ch : list) {
    if (ch == ',')
      flush();
    else if (ch != ' ')
      token += ch;
  }
  flush();
  return out;
}

}  // namespace demfit::diagnose
