#pragma once
// Checks a study against what its model produces, before any store or output is written:
// one evaluation at the initial point (initial values of the variables, fixed parameters, model
// defaults) and then, for every target,
//   - the curve exists (else the error lists the model's curves),
//   - the target's units are converted to the model's (units.hpp), a dimension mismatch refused,
//   - the target's x-range overlaps the model's x-range at the initial point.
#include <optional>

#include "demfit/identify/evaluator.hpp"
#include "demfit/identify/model.hpp"
#include "demfit/identify/study.hpp"
#include "demfit/identify/study_spec.hpp"

namespace demfit::identify {

// Returns `spec` with the target data in the model's units (labels = the model's); throws
// std::runtime_error "study: targets[i].<field>: ..." otherwise. The point evaluated is the study's
// run 0/0 exactly (the initial values through the loop's unit coordinates); with `initial`, that
// run is handed back so the loop does not evaluate it a second time (RunOptions::initial_run).
StudySpec preflight_study(const StudySpec& spec, const Model& model, const EvaluationContext& context,
                          std::optional<InitialRun>* initial = nullptr);

// The same, with the initial point evaluated by `evaluator` (e.g. on an MPI worker rank, so rank 0
// only schedules and the run uses the workers' settings).
StudySpec preflight_study(const StudySpec& spec, const Model& model, Evaluator& evaluator,
                          std::optional<InitialRun>* initial = nullptr);

// The check of a study about to run with `options` (options.resolved_model set, as the front ends
// set it): the same, except that on options.resume, when the store in options.output_dir already
// holds run 0/0 as a successful run of the same resolved model and seed with the initial point's
// parameters bit for bit, its stored curves stand for the evaluation. The loop takes that stored
// run anyway, and the initial point of a DEM study costs a whole simulation. Otherwise `evaluator`
// evaluates the initial point and options.initial_run receives the run (a stored run that failed
// is evaluated again, as the check needs curves). The result is the same either way: the model is
// deterministic in its parameters, resolved model and seed.
StudySpec preflight_study(const StudySpec& spec, const Model& model, Evaluator& evaluator, RunOptions& options);

}  // namespace demfit::identify
