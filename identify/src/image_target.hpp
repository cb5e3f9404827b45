#pragma once
// Internal: a study target read from a drum photo (demfit::imaging does the image work).
#include <filesystem>

#include "demfit/identify/model.hpp"
#include "demfit/identify/study_spec.hpp"

namespace demfit::identify::detail {

// The photo's free-surface profile as a curve x_mm, z_mm (drum frame: origin on the axis,
// x right, z up; millimetres). image.file resolves against base_dir when relative. Throws
// std::runtime_error (one line naming the file and the fix) when the photo cannot be read or
// holds no surface.
Curve read_image_target(const ImageTargetSpec& image, const std::filesystem::path& base_dir);

}  // namespace demfit::identify::detail
