#pragma once
// The registry of contact laws. A simulation names its law by ContactLawKind (the case files'
// "contact": {"law": name}); `with_contact_law` turns kind and parameters into the law TYPE
// with one exhaustive switch (-Werror=switch lists it when a kind is added), and every place
// that depends on the law (force loops, particle compliances, time step, history storage) goes
// through it. The loops are templates on the law type: no virtual call per contact.
//
// Adding a law (docs/extending.md): its header with a type satisfying `ContactLaw` below, its
// ContactLawKind value (parameters.hpp), one row in kContactLaws, one case in with_contact_law
// and one alternative in ContactLawStates.
#include <concepts>
#include <optional>
#include <stdexcept>
#include <string_view>
#include <type_traits>
#include <variant>
#include <vector>

#include "demfit/dem_core/contact_law_hertz.hpp"
#include "demfit/dem_core/contact_law_linear.hpp"

namespace demfit::dem_core {

/// What the simulation asks of a law type; LsDynaLinearLaw and HertzMindlinLaw are examples.
/// - `History`: per-contact memory, default = a new contact, trivially copyable, first member the
///   tangential spring (negated when a pair's members swap roles at a reorder; a law switch
///   keeps it and restarts the rest);
/// - `for_pairs` / `for_wall`: the law from the physical parameters;
/// - `particle_compliance`: a particle's half of a contact's springs (the loops sum both halves
///   into ContactGeometry; a wall contact divides the particle's normal one by SFP);
/// - `time_step`: automatic step and stability limit;
/// - `restarts_history(before, after)`: true when changing the parameters between two force
///   evaluations must restart the memory beyond the tangential spring;
/// - `force`: the loads of one contact, updating its history;
/// - `elastic_energy`: the energy of its springs as `force` left them (asked for only by probes).
template <class Law>
concept ContactLaw = requires(const Law law, const ContactGeometry& g, typename Law::History& history,
                              const ContactParameters& p, const WallContactParameters& w, const Material& m,
                              const TimeStepInputs& inputs, double radius, double dt) {
  requires std::is_trivially_copyable_v<typename Law::History>;
  { history.tangential_displacement } -> std::same_as<Vec3&>;
  { Law::for_pairs(p) } -> std::same_as<Law>;
  { Law::for_wall(p, w) } -> std::same_as<Law>;
  { Law::particle_compliance(m, radius, p) } -> std::same_as<ParticleCompliance>;
  { Law::time_step(inputs) } -> std::same_as<TimeStepEstimate>;
  { Law::restarts_history(p, p) } -> std::same_as<bool>;
  { law.force(g, history, dt) } -> std::same_as<ContactForce>;
  { law.elastic_energy(g, history) } -> std::same_as<double>;
};

/// One row per ContactLawKind: its name in case files and messages.
struct ContactLawRow {
  ContactLawKind kind;
  std::string_view name;
};
inline constexpr ContactLawRow kContactLaws[] = {
    {ContactLawKind::lsdyna_linear, "lsdyna_linear"},  // LS-DYNA linear (+ effects library)
    {ContactLawKind::hertz_mindlin, "hertz_mindlin"},  // Hertz–Mindlin, restitution damping
};

/// Name of `kind` in case files; throws std::logic_error for a kind without a row.
inline std::string_view contact_law_name(ContactLawKind kind) {
  for (const ContactLawRow& row : kContactLaws)
    if (row.kind == kind) return row.name;
  throw std::logic_error("ContactLawKind without a row in kContactLaws (contact_laws.hpp)");
}
/// The kind named `name`, or nothing.
inline std::optional<ContactLawKind> contact_law_kind(std::string_view name) {
  for (const ContactLawRow& row : kContactLaws)
    if (row.name == name) return row.kind;
  return std::nullopt;
}

/// The one dispatch on the law: calls `visit(std::type_identity<Law>{})` with the law type that
/// `kind` and `contact` select and returns its result. The effects law is the linear law with
/// an effect on; with every effect off the plain law runs (bit-identical, no extra cost). The
/// Hertz law comes with the rolling resistance of contact.rolling_model (cdt or epsd2).
template <class Visit>
decltype(auto) with_contact_law(ContactLawKind kind, const ContactParameters& contact, Visit&& visit) {
  switch (kind) {
    case ContactLawKind::lsdyna_linear:
      if (contact.effects_enabled()) return visit(std::type_identity<LsDynaEffectsLaw>{});
      return visit(std::type_identity<LsDynaLinearLaw>{});
    case ContactLawKind::hertz_mindlin:
      switch (contact.rolling_model) {  // the epsd2 spring keeps a torque per contact: its own type
        case RollingModel::constant_torque:
          return visit(std::type_identity<HertzMindlinLaw>{});
        case RollingModel::elastic_plastic:
          return visit(std::type_identity<HertzEpsd2Law>{});
      }
      break;
  }
  throw std::logic_error("with_contact_law: a ContactLawKind without a case");
}

/// What the simulation keeps for law `Law`: the contact histories of the neighbour-list pairs
/// and of the particle–wall slots (aligned with their arrays) and the per-wall laws.
template <ContactLaw Law>
struct ContactLawState {
  std::vector<typename Law::History> pair_history{};
  std::vector<typename Law::History> wall_history{};
  std::vector<Law> wall_laws{};        ///< one per wall (valid while Simulation::wall_laws_valid_)
  ContactParameters evaluated_with{};  ///< parameters of the last force evaluation
};

/// The simulation's per-law state: one alternative per law type of with_contact_law.
using ContactLawStates = std::variant<ContactLawState<LsDynaLinearLaw>, ContactLawState<LsDynaEffectsLaw>,
                                      ContactLawState<HertzMindlinLaw>, ContactLawState<HertzEpsd2Law>>;

}  // namespace demfit::dem_core
