// `demfit reproduce table2`: Table 2 with numbers (see reproduce_tables.hpp).
#include <string>

#include "number_text.hpp"
#include "demfit/cases/reproduce_tables.hpp"

namespace demfit::cases {

std::string format_table2(const OriginalParticle& original, double phi, const std::vector<double>& scales) {
  std::string out;
  out += "Table 2: coarse-graining models (r0 = " + fmt("%.3g", original.radius * 1e3) +
         " mm, rho0 = " + fmt("%.0f", original.density) + " kg/m^3, phi = " + fmt("%.2f", phi) + ")\n\n";
  out +=
      "| model | s | radius [mm] | paper's printed radius [mm] | particle volume [mm^3] | particle mass [mg] "
      "| true density [kg/m^3] | total mass / M0 | particles per original |\n";
  out += "|---|---|---|---|---|---|---|---|---|\n";
  for (CoarseGraining model : {CoarseGraining::scg, CoarseGraining::cvf}) {
    for (double s : scales) {
      const CoarseParticle p = coarse_grain(model, s, phi, original);
      const double printed =
          model == CoarseGraining::scg ? p.radius : paper_printed_cvf_radius(s, phi, original.radius);
      const double per_original = p.total_mass_factor * original.density * sphere_volume(original.radius) / p.mass;
      out += "| " + std::string(model == CoarseGraining::scg ? "SCG" : "CVF") + " | " + fmt("%g", s) + " | " +
             fmt("%.4f", p.radius * 1e3) + " | " + fmt("%.4f", printed * 1e3) + " | " +
             fmt("%.4f", p.volume * 1e9) + " | " + fmt("%.4f", p.mass * 1e6) + " | " + fmt("%.1f", p.density) +
             " | " + fmt("%.2f", p.total_mass_factor) + " | " + fmt("%.5f", per_original) + " |\n";
    }
  }
  out +=
      "\nNote on the CVF radius: the paper prints r_CVF = phi^(1/3) s r0, which contradicts its own\n"
      "volume row (v_CVF = s^3 v0 / phi) and density row (rho_CVF = phi rho0, mass s^3 m0).\n"
      "demfit uses the self-consistent radius r_CVF = s r0 phi^(-1/3): the coarse particle occupies\n"
      "the bulk volume of the s^3 particles it replaces. The printed value is listed for comparison.\n"
      "Checks: volume = 4/3 pi r^3 and mass = density x volume hold in every row (tests/cases).\n";
  return out;
}

}  // namespace demfit::cases
