#pragma once
// The case kinds: one row per kind (its case-file name, its own section, what it models and every
// curve it can produce with units). Code that differs per kind dispatches with an exhaustive
// `switch (spec.kind)` without `default` (built with -Werror=switch), so adding a CaseKind makes
// the compiler list every site; docs/cases.md "Adding a case" walks through them.
#include <string>
#include <string_view>
#include <vector>

#include "demfit/cases/case_spec.hpp"
#include "demfit/identify/model.hpp"

namespace demfit::cases {

// When a kind produces a curve: always, or only with a case-file option on.
enum class CurveCondition { always, pellet_unload, drum_image, mesh_heap_angle, mesh_discharge_mass, mesh_part_torque };

// A curve of a case kind and when the kind produces it.
struct CaseCurve {
  identify::CurveDescriptor curve;
  CurveCondition produced = CurveCondition::always;
};

struct CaseKindRow {
  CaseKind kind;
  const char* name;     // "case" in the case file
  const char* section;  // the kind's own case-file section (no other kind may carry it)
  const char* summary;  // what it models (docs/spec.md section)
  std::vector<CaseCurve> curves;
};

// Every case kind, in CaseKind order.
const std::vector<CaseKindRow>& case_kind_table();
const CaseKindRow& case_kind_row(CaseKind kind);
// nullptr when no kind has this case-file name.
const CaseKindRow* find_case_kind(std::string_view name);
// "pellet_compression", "rotary_drum" or "mesh_container" (every name, for error messages).
std::string case_kind_names();

// The curves a run of `spec` returns (its kind's curves whose option is on), names and labels.
std::vector<identify::CurveDescriptor> produced_curves(const CaseSpec& spec);

// The descriptor of one curve of `kind` by name (a logic error when the row lacks it): the run
// code builds its curves from these, so names and labels have one source.
const identify::CurveDescriptor& case_curve(CaseKind kind, std::string_view name);
identify::Curve empty_curve(CaseKind kind, std::string_view name);

}  // namespace demfit::cases
