// Drum photos from Python: demfit.surface_profile gives the free-surface profile of a photo (a file,
// or a grey image as a 2-D NumPy array) in the drum frame, as `demfit target from-image` writes it
// to free_surface.csv, but in metres. The extraction rule is imaging/surface.hpp.
#include <optional>
#include <string>

#include "bindings.hpp"
#include "demfit/imaging/imaging.hpp"

namespace demfit::python {

namespace {

struct Profile {
  imaging::SurfaceProfile profile;
  imaging::SurfaceLine line;
};

// A photo file, or a 2-D array of grey levels (row 0 = top; 0 black .. 1 white).
imaging::GreyImage grey_image(const py::object& photo) {
  if (py::isinstance<py::str>(photo) || py::hasattr(photo, "__fspath__"))
    return imaging::read_grey_image(py::str(photo).cast<std::string>());
  const auto array = py::array_t<float, py::array::c_style | py::array::forcecast>::ensure(photo);
  if (!array || array.ndim() != 2)
    input_error("photo: give an image file name or a 2-D array of grey levels (0 black .. 1 white, row 0 on top)");
  imaging::GreyImage image;
  image.height = static_cast<int>(array.shape(0));
  image.width = static_cast<int>(array.shape(1));
  image.value.assign(array.data(), array.data() + array.size());
  image.source = "photo array";
  return image;
}

Profile surface_profile(const py::object& photo, double diameter, std::optional<double> threshold,
                        bool material_is_dark, double margin, int points) {
  imaging::check_drum_diameter(diameter, "diameter");
  imaging::ProfileOptions options;
  options.threshold = threshold ? *threshold : -1.0;
  if (threshold && !(*threshold >= 0.0 && *threshold <= 1.0))
    input_error("threshold " + std::to_string(*threshold) +
                ": give a grey level in [0, 1] (0 black, 1 white), or None for Otsu's");
  options.material_is_dark = material_is_dark;
  options.margin = margin;
  options.points = points;
  const imaging::GreyImage image = grey_image(photo);
  Profile out;
  {
    py::gil_scoped_release release;
    out.profile = imaging::extract_surface(image, imaging::DrumFrame{diameter}, options);
    out.line = imaging::fit_surface_line(out.profile);
  }
  return out;
}

}  // namespace

void register_imaging(py::module_& m) {
  py::class_<Profile>(m, "SurfaceProfile", "The free surface of a drum photo in the drum frame (metres).")
      .def_property_readonly(
          "x", [](const Profile& p) { return to_array(p.profile.x); }, "[m] abscissae, right as seen, from the axis")
      .def_property_readonly(
          "z", [](const Profile& p) { return to_array(p.profile.z); }, "[m] bed surface height above the axis")
      .def_property_readonly("threshold", [](const Profile& p) { return p.profile.threshold_used; },
                             "grey level used (Otsu's or the given one)")
      .def_property_readonly("compared_radius", [](const Profile& p) { return p.profile.compared_radius; },
                             "[m] (1 - margin) R")
      .def_property_readonly("pixel_size", [](const Profile& p) { return p.profile.pixel_size; }, "[m]")
      .def_property_readonly("angle_deg", [](const Profile& p) { return p.line.angle_deg; },
                             "[deg] straight-line fit; negative = bed lifted on the left")
      .def_property_readonly("residual_rms", [](const Profile& p) { return p.line.residual_rms; },
                             "[m] RMS of the profile about the straight line");
  m.def("surface_profile", &surface_profile, py::arg("photo"), py::arg("diameter"), py::arg("threshold") = py::none(),
        py::arg("material_is_dark") = true, py::arg("margin") = 0.1, py::arg("points") = 41,
        "The free-surface profile of a square drum photo spanning the inner diameter [m] (as `demfit target "
        "from-image`): photo is an image file (PNG, JPEG) or a 2-D array of grey levels. threshold: grey level "
        "in [0, 1], None = Otsu's. material_is_dark False for inverted contrast. margin: fraction of the radius "
        "ignored at the wall. points: abscissae of the profile.");
}

}  // namespace demfit::python
