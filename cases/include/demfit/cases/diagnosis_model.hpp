#pragma once
// The model a diagnosis (diagnose/workflow.hpp) fits and the candidate effects it may name, as every
// front end that diagnoses a study needs them (the command line, the Python module): the analytic
// family with its effect terms for the "analytic" model, the cases effect catalogue for DEM cases
// (cases/effect_catalogue.hpp), and for a study with experiments identify's ExperimentSetModel
// over one model per experiment with the union of their candidates. An external program
// (identify/external_model.hpp) gets the candidates its study declares as template parameters.
#include <filesystem>
#include <memory>
#include <vector>

#include "demfit/diagnose/effect.hpp"
#include "demfit/identify/model.hpp"
#include "demfit/identify/study_spec.hpp"

namespace demfit::cases {

// The study's model and its candidates. An effect is left out, with a note on stderr, when one of
// its parameters is a study variable, does not exist under the case's contact law, or already
// differs from its off value in the model (it is then part of the base model). Throws
// std::runtime_error (one line) for a model override diagnose does not understand. An external
// model's runs go to `output_dir`/external_runs (output_dir marked as a diagnose folder when a
// run creates it); an external study without an output folder is refused.
std::unique_ptr<identify::Model> diagnosis_model_and_candidates(const identify::StudySpec& spec,
                                                                std::vector<diagnose::EffectCandidate>& candidates,
                                                                const std::filesystem::path& output_dir = {});

// Expensive, chaotic DEM models (demfit's kernel or an external program) get diagnose's options for
// them (diagnose::expensive_model_options); the analytic model does not.
bool uses_dem(const identify::StudySpec& spec);

// diagnose fits least squares at the target points, so an image target's profile_area metric is
// read as mse at the photo's abscissae (the same profile z(x)); a note on stderr says so.
identify::StudySpec with_pointwise_metrics(identify::StudySpec spec);

}  // namespace demfit::cases
