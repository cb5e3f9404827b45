#pragma once
// LS-DYNA keyword export of identified DEM parameters, fixed 10-character fields (docs/spec.md 4).
// Which parameter fills which field comes from the model's descriptors
// (ParameterDescriptor::lsdyna_field, "*CONTROL_DISCRETE_ELEMENT NORMK"; for the DEM cases, the
// parameter table's LS-DYNA column): this file knows the cards, never the parameter names. A field
// whose parameter is not in `parameters` gets the descriptor's default (the DEM cases: LS-DYNA's;
// FRICD without one = FRICS); a field no descriptor names is left blank.
// Card layout written (LS-DYNA Keyword User's Manual, Vol. I; blank fields = LS-DYNA default):
//   *CONTROL_DISCRETE_ELEMENT
//     card 1: NDAMP TDAMP FRICS FRICR NORMK SHEARK CAP MXNSC   (CAP, MXNSC blank)
//     card 2: GAMMA VOL ANG GAP IGNORE NBUF PARALLEL           (all blank)
//     card 3: LNORM LSHEAR (unused) FRICD DC                   (LNORM, LSHEAR blank)
//   *DEFINE_DE_TO_SURFACE_COUPLING
//     card 1: SLAVE MASTER STYPE MTYPE     placeholders 1 2 0 0 (edit for your model)
//     card 2: FRICS FRICD DAMP BSORT ...   wall_frics wall_fricd wall_damp
//   wall_sfp is written as a comment: its field position differs between LS-DYNA versions.
#include <filesystem>
#include <string>
#include <vector>

#include "demfit/identify/model.hpp"

namespace demfit::identify {

// Formats a number into exactly 10 characters, right-aligned, with as many significant digits
// as fit (exponent shortened to e-5 style when needed). Throws if it cannot fit.
std::string lsdyna_field(double value);
// `title` and each of `comments` become "$ " comment lines; control characters in them are turned
// into blanks, so no text can leave its comment line. `model_parameters`: the model's
// descriptors (for the DEM cases: cases::parameter_descriptors()); every effect parameter among
// them without an LS-DYNA field (off value set, lsdyna_field empty) that `parameters` holds at a
// value other than its off value gets a "$ WARNING" comment: LS-DYNA cannot carry it.
std::string lsdyna_keywords(const ParameterSet& parameters, const std::vector<ParameterDescriptor>& model_parameters,
                            const std::string& title, const std::vector<std::string>& comments = {});
void write_lsdyna_keywords(const std::filesystem::path& path, const ParameterSet& parameters,
                           const std::vector<ParameterDescriptor>& model_parameters, const std::string& title,
                           const std::vector<std::string>& comments = {});
// Reads the cards written above back into the names of `model_parameters` (tests, round trips).
ParameterSet parse_lsdyna_keywords(const std::string& text, const std::vector<ParameterDescriptor>& model_parameters);

}  // namespace demfit::identify
