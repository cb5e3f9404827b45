#pragma once
// demfit::imaging — image targets for drum experiments. One include for all of it.
#include "demfit/imaging/image.hpp"
#include "demfit/imaging/occupancy.hpp"
#include "demfit/imaging/overlay.hpp"
#include "demfit/imaging/profile_metrics.hpp"
#include "demfit/imaging/surface.hpp"
