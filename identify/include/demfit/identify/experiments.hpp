#pragma once
// Several experiments in one study: e.g. the same drum at 15 and 45 rpm, or a
// pellet compression and a drum, all sharing the study's variables.
//
// A design point is evaluated as all its experiments. Each experiment's model receives its own
// default parameters, its fixed_parameters, and the study parameters its model accepts (a
// variable goes to every experiment whose model accepts it; run_study refuses one that no model
// accepts). The curves of a point are the union of the experiments' curves, each key qualified
// "<experiment>/<curve>", so targets, the objective (sum of all experiments' target terms), the
// store and the report see one CurveSet per point.
//
// ExperimentSetModel is a Model, so everything that runs a Model (diagnose, tests) can run a
// study with experiments; the study loop and the evaluators (threads, MPI ranks) split a point
// into one job per experiment instead, so the experiments of a point run in parallel.
#include <memory>
#include <string>
#include <vector>

#include "demfit/identify/evaluator.hpp"
#include "demfit/identify/model.hpp"
#include "demfit/identify/study_spec.hpp"

namespace demfit::identify {

class ExperimentSetModel final : public Model {
 public:
  // One model per spec.experiments entry, in order. Throws std::invalid_argument when the counts
  // differ or the spec has no experiments.
  ExperimentSetModel(const StudySpec& spec, std::vector<std::unique_ptr<Model>> models);

  // Union of the experiments' parameter names (sorted).
  // Their descriptors; a name several experiments accept gets the intersection of their ranges.
  std::vector<ParameterDescriptor> parameters() const override;
  // "<experiment>/<curve>" for every experiment's declared curve; empty when one declares none.
  std::vector<CurveDescriptor> curves() const override;
  // Empty: every experiment brings its own defaults (experiment_parameters).
  ParameterSet default_parameters() const override { return {}; }
  // Runs the experiments one after the other; curves keyed "<experiment>/<curve>". Throws the
  // first experiment's error prefixed "experiment '<name>': ".
  CurveSet evaluate(const ParameterSet& parameters, const EvaluationContext& context) const override;

  std::size_t size() const { return experiments_.size(); }
  const std::string& name(std::size_t experiment) const { return experiments_[experiment].name; }
  const Model& model(std::size_t experiment) const { return *experiments_[experiment].model; }
  // What experiment e's model receives: its defaults, its fixed parameters, then the given
  // parameters that its model accepts.
  ParameterSet experiment_parameters(std::size_t experiment, const ParameterSet& parameters) const;

 private:
  struct Experiment {
    std::string name;
    std::unique_ptr<Model> model;
    ParameterSet fixed;
    std::vector<std::string> accepted;
  };
  std::vector<Experiment> experiments_;
};

// The model as a set of experiments, or null for a plain model (the one place that looks behind
// the Model interface: a set's experiments are evaluated as separate jobs).
const ExperimentSetModel* as_experiment_set(const Model& model);

// The models a job's experiment index selects: the experiments of an ExperimentSetModel, or the
// model itself as experiment 0.
std::vector<const Model*> experiment_models(const Model& model);

// Splits design points (complete parameter sets of the model) into one job per (point,
// experiment), job k = point k / E, experiment k % E, and joins the outcomes back per point.
class PointJobs {
 public:
  PointJobs(const Model& model, const std::vector<ParameterSet>& points);
  const std::vector<EvaluationJob>& jobs() const { return jobs_; }
  // Records job `job`'s outcome. When it was its point's last experiment, returns true and sets
  // `point` and `outcome` to the point's combined outcome (combine_experiment_outcomes).
  bool finish(std::size_t job, const EvaluationOutcome& part, std::size_t& point, EvaluationOutcome& outcome);

 private:
  std::vector<std::string> names_;  // {""} for a plain model
  std::vector<EvaluationJob> jobs_;
  std::vector<std::vector<EvaluationOutcome>> parts_;
  std::vector<std::size_t> missing_;
};

// Joins the outcomes of one point's experiments (in experiment order) into the point's outcome:
// ok when all are ok, curves keyed "<name>/<curve>", error of the first failed experiment
// prefixed with its name, wall time = sum (the cost of the point). A single unnamed experiment
// is returned unchanged.
EvaluationOutcome combine_experiment_outcomes(const std::vector<std::string>& names,
                                              std::vector<EvaluationOutcome> outcomes);

// The key of a curve of experiment `experiment` in a point's CurveSet.
std::string experiment_curve_key(const std::string& experiment, const std::string& curve);

}  // namespace demfit::identify
