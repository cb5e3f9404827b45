// Image targets: the photo's surface profile in millimetres. The extraction
// rule (compared circle, Otsu threshold, bed connected to the bottom, sub-pixel surface) is
// demfit::imaging's, so the simulated side, built from an occupancy image by the same code,
// means the same thing.
#include "image_target.hpp"

#include <stdexcept>

#include "demfit/imaging/image.hpp"
#include "demfit/imaging/surface.hpp"

namespace demfit::identify::detail {

Curve read_image_target(const ImageTargetSpec& image, const std::filesystem::path& base_dir) {
  const std::filesystem::path file = image.file.is_absolute() ? image.file : base_dir / image.file;
  const imaging::GreyImage photo = imaging::read_grey_image(file);
  imaging::ProfileOptions options;
  options.threshold = image.threshold;
  options.material_is_dark = image.material_is_dark;
  options.margin = image.margin;
  options.points = image.points;
  const imaging::SurfaceProfile profile = imaging::extract_surface(photo, imaging::DrumFrame{image.diameter}, options);
  if (profile.x.size() < 2)
    throw std::runtime_error("image target '" + file.string() +
                             "': fewer than 2 surface points found; check "
                             "image_diameter, image_margin and image_threshold");
  Curve curve{"x_mm", "z_mm", {}, {}};
  for (std::size_t i = 0; i < profile.x.size(); ++i) {
    curve.x.push_back(1e3 * profile.x[i]);  // m -> mm
    curve.y.push_back(1e3 * profile.z[i]);
  }
  return curve;
}

}  // namespace demfit::identify::detail
