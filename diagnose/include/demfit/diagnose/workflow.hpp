#pragma once
// The diagnosis workflow: 1. fit the base model, 2. decide noise vs structure,
// 3. screen the candidate effects by a score test and re-fit the best few with their extra
// parameters, 4. name an effect only if it passes the information criterion AND leaves a
// residual that passes the noise tests, 5. otherwise say plainly that the residual is unexplained.
#include <string>
#include <vector>

#include "demfit/diagnose/effect.hpp"
#include "demfit/diagnose/least_squares.hpp"
#include "demfit/diagnose/model_scatter.hpp"
#include "demfit/diagnose/residual_tests.hpp"
#include "demfit/diagnose/screening.hpp"
#include "demfit/identify/study_spec.hpp"

namespace demfit::diagnose {

struct DiagnoseOptions {
  double noise_sigma = 0.0;  // > 0: given noise level (y units, all targets); 0 = estimate per target
  double alpha = 0.01;       // family-wise level of the residual tests on the base fit
  // Family-wise level of the tests on an augmented fit before its effect may be named. Larger
  // than alpha on purpose: naming needs positive evidence that the residual became noise, so a
  // candidate that only half-explains an effect outside the list is not named (docs/diagnose.md).
  double alpha_named = 0.05;
  double bic_threshold = 10.0;  // name an effect only if BIC(base) - BIC(augmented) exceeds this
  // Base fits: study initial values, then (only if that fit ends on a bound of some variable)
  // v_lo + (v_hi - v_lo) i / base_starts, i = 1 .. base_starts - 1.
  int base_starts = 2;
  // Candidates re-identified after screening: every one whose score is at least
  // refit_score_ratio x the best score (0: all of them, the default for cheap models), and at least
  // the refit_best highest. With DEM trajectory noise the screening scores of different
  // effects come within 25 % of each other, so the ranking alone must not decide which are compared.
  int refit_best = 2;
  double refit_score_ratio = 0.0;
  // Progress lines on stderr (base fit, screening, each re-fit with its evaluations and seconds).
  bool progress = false;
  // Local fits per re-identified candidate (1..3). The first starts at the base optimum with the
  // score test's estimate and the base/screening Jacobian (no new finite differences); the others
  // (study initial values + estimate, + mid-range effect) run only if the first does not pass.
  int refit_starts = 3;
  // Model runs of a global surrogate search over base + effect variables (surrogate_start.hpp) per
  // re-fitted candidate, made only when no candidate passed with its local starts; its point is
  // assessed, then fitted locally and assessed, like the other starts. 0 = none. A DEM chi-square
  // whose run-to-run scatter is as deep as an effect's valley can hide that valley from every
  // local start (docs/diagnose.md, step 4). With the model's scatter in the criterion, the base
  // variables get the same search first, so that the base is not judged at a worse optimum than
  // the re-fits it is compared with.
  int refit_search_evaluations = 0;
  double screen_step = 0.02;  // score-test perturbation, fraction of the effect range
  // Replicas of the base optimum, each with the variables moved by k x 1e-7 of their ranges (a
  // round-off-sized change), that measure the model's own scatter (model_scatter.hpp); 0 = none
  // (smooth models). A target whose scatter exceeds scatter_threshold x its data noise has its
  // residuals whitened by data noise + AR(1) scatter, and the base fit is refined under that noise.
  int scatter_replicas = 0;
  double scatter_threshold = 0.25;
  // The data's own run-to-run scatter, as a multiple k of one model run's scatter variance, counted
  // in the noise model beside the model run's (Sigma_t = sigma_data^2 I + (1 + k) sigma_scatter^2
  // R(rho)): 0 when it is negligible (data averaged over many realisations, or a material with far
  // more particles than a coarse model); 1 when the data are one run of a flow as chaotic as the
  // model's (a synthetic twin made by `demfit simulate`): the residual then holds two independent
  // trajectories, and counting one left the whitened lag-1 correlation of a correct model at
  // 0.14-0.28 instead of 0 (docs/diagnose.md, "What Sigma leaves out"); 1/m for a mean of m runs.
  double data_scatter_ratio = 0.0;
  FitOptions fit;
};

// Options for an expensive model whose curves change chaotically under small parameter changes
// (DEM): central differences with a step of 2 % of each range (the difference must be dominated
// by the parameter's systematic effect, not by trajectory noise; small enough for the
// linearisation), fits stopped when the chi-square gains less than 0.1 per step (far below the BIC
// threshold of 10), a screening step of 20 % of each effect's range (a weak effect switched on by
// 2 % would drown in trajectory noise; the score statistic does not depend on the step's size),
// one start for the base fit and per re-fit, at most 60 evaluations per fit, and 4 replicas of
// the base optimum to measure the trajectory scatter (the s = 4 drum's true effect left
// RMS/sigma 1.8-2.3 against the data noise alone, so it could never be named).
// docs/diagnose.md gives the measured costs.
DiagnoseOptions expensive_model_options();

enum class Verdict {
  no_missing_effect,       // base residual is noise
  effect_identified,       // one candidate passes the criterion and whitens the residual
  unexplained_structural,  // structure, and no candidate explains it
  // Another plausible candidate fits about as well: its delta BIC also exceeds the threshold (the
  // criterion favours it over the base) and is within the threshold of the best one's, whether or
  // not its residual passed the noise tests.
  ambiguous,
};
const char* verdict_text(Verdict verdict);

struct CandidateFit {
  std::string effect;
  FitResult fit;
  ResidualAnalysis analysis;
  double bic = 0.0, aicc = 0.0;
  // The chi-square in BIC and AICc: the fit's own, or, when the model's scatter is in the noise
  // model, the mean over Diagnosis::criterion_replicas fresh replicas of the optimum.
  double criterion_chi_square = 0.0;
  double delta_bic = 0.0;  // BIC(base) - BIC(this): > 0 favours the effect
  double delta_aicc = 0.0;
  bool passes = false;  // delta_bic > threshold and residual passes the noise tests
};

struct Diagnosis {
  std::vector<FitTarget> targets;       // with the noise level used (and the scatter's whitening)
  std::vector<TargetScatter> scatter;   // measured model scatter per target (empty: not measured)
  bool scatter_in_noise_model = false;  // some target whitened by it
  std::vector<FitVariable> base_variables;
  FitResult base;
  ResidualAnalysis base_analysis;  // under the noise model used (with the model's scatter if measured)
  // The base residual's tests against the data noise alone. Candidates are compared whenever this
  // is structural; with the model's scatter in the noise model, an effect is named only if it wins
  // under that model, and a base residual consistent with data noise + scatter is reported as
  // no missing effect beyond the model's own scatter.
  ResidualAnalysis base_analysis_data_noise;
  double base_bic = 0.0, base_aicc = 0.0;
  std::vector<ScreeningScore> screening;  // candidate order
  std::vector<CandidateFit> refits;       // the best few, in screening rank order
  Verdict verdict = Verdict::no_missing_effect;
  int chosen = -1;        // index into refits when an effect is identified
  std::vector<int> tied;  // ambiguous: the refits that explain it equally well
  std::vector<EffectCandidate> candidates;
  // As used: DiagnoseOptions::bic_threshold, raised by 2 x sqrt(2 / criterion_replicas) x
  // scatter_chi_square_sd when the model's scatter is in the noise model (the chi-square of one
  // evaluation is itself that noisy; the criterion compares means over that many replicas).
  double bic_threshold = 10.0;
  // Spread of the base's replicas' chi-squares (0: not measured); of the searched base point's runs
  // when that point supplies the base criterion (base_search_*).
  double scatter_chi_square_sd = 0.0;
  // > 0: the criterion's chi-squares (base and re-fits) are means over this many fresh replicas of
  // each optimum (runs differing only in round-off), not the one lucky run a fit keeps.
  int criterion_replicas = 0;
  double base_criterion_chi_square = 0.0;  // the chi-square in base_bic and base_aicc
  // With the model's scatter in the noise model: whether the base fit refined under it moved from
  // the first optimum. If it did not, base_criterion_chi_square is the mean of the scatter replicas
  // already run (mapped to the whitened targets); if it did, of fresh replicas of the new optimum.
  bool base_refined = false;
  bool noise_given = false;        // sigma given (--noise) rather than estimated
  double data_scatter_ratio = 0.0;  // the data's own scatter counted in the noise model (--data-scatter)
  int refit_search_evaluations = 0;  // runs of the surrogate search per failing re-fit (--refit-search)
  // The surrogate search over the base variables (made when refit_search_evaluations > 0 and the
  // criterion is replicated): its runs, its point (empty: not made, or it chose the base fit's own
  // point) and the mean chi-square of criterion_replicas fresh runs there. base_criterion_chi_square
  // is the lower of this and the base fit's optimum's.
  int base_search_evaluations = 0;
  std::vector<double> base_search_values;
  double base_search_criterion_chi_square = 0.0;
  std::vector<std::string> notes;  // plain-language statements for the report
  // Model evaluations spent: base fit (with the scatter replicas), screening, re-fits, total; wall time [s].
  int base_evaluations = 0, screening_evaluations = 0, refit_evaluations = 0, evaluations = 0;
  double wall_seconds = 0.0;
  std::string summary;  // one paragraph: the verdict with its numbers
};

// Information criteria with the likelihood of Gaussian noise of known sigma (normalised
// residual r): BIC = |r|^2 + k ln n, AICc = |r|^2 + 2k + 2k(k+1)/(n-k-1).
double bic(double chi_square, int parameters, int points);
double aicc(double chi_square, int parameters, int points);

// Candidates to re-fit (indices into `screening`), best score first: every one scoring at least
// options.refit_score_ratio x the best, and at least the options.refit_best highest.
std::vector<int> refit_order(const std::vector<ScreeningScore>& screening, const DiagnoseOptions& options);

// Whether a candidate's re-fit start `trial` (assessed) replaces the start kept so far: when it
// passes the criterion (the starts stop there), or when its criterion chi-square is lower. A start
// is judged on its own: a passing one is not discarded because an earlier, failing one had the lower
// chi-square, and on a scattering model the fit's own chi-square, which rewards a lucky trajectory,
// does not choose between starts.
bool replaces_kept_start(const CandidateFit& kept, const CandidateFit& trial);

// Sets verdict/chosen/tied from d.refits: the passing re-fit with the largest delta BIC is named
// unless another plausible one (delta BIC > threshold, residual tests passed or not) has a delta
// BIC within the threshold of it: then "ambiguous" and nothing is named.
void decide_verdict(Diagnosis& d, double bic_threshold);

// Runs the workflow on the study's variables (bounds, initial values), fixed parameters and mse
// targets. Throws std::runtime_error (one line) on a curve_mapping target, a candidate parameter
// the model does not accept, or a base model that cannot be evaluated.
Diagnosis run_diagnosis(const identify::StudySpec& study, const identify::Model& model,
                        const std::vector<EffectCandidate>& candidates, const DiagnoseOptions& options);

}  // namespace demfit::diagnose
