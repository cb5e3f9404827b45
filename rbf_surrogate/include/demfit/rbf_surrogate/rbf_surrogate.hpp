#pragma once
// Umbrella header for the rbf_surrogate module.
#include "demfit/rbf_surrogate/adaptive_infill.hpp"
#include "demfit/rbf_surrogate/bounds.hpp"
#include "demfit/rbf_surrogate/design.hpp"
#include "demfit/rbf_surrogate/expected_improvement.hpp"
#include "demfit/rbf_surrogate/expensive.hpp"
#include "demfit/rbf_surrogate/kriging.hpp"
#include "demfit/rbf_surrogate/optimize.hpp"
#include "demfit/rbf_surrogate/rbf_network.hpp"
#include "demfit/rbf_surrogate/srsm.hpp"
