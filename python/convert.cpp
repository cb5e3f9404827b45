// Conversions between the library's values and Python's: curves as NumPy arrays, parameter sets
// as dicts, JSON documents as Python objects.
#include <cmath>

#include "bindings.hpp"

namespace demfit::python {

nlohmann::json to_json(const py::handle& object, const std::string& field) {
  const py::module_ json = py::module_::import("json");
  std::string text;
  try {
    text = json.attr("dumps")(object, py::arg("allow_nan") = false).cast<std::string>();
  } catch (const py::error_already_set& e) {
    input_error(field + ": not representable as JSON (" + std::string(py::str(e.value())) +
                "); give numbers, strings, booleans, lists and dicts");
  }
  return nlohmann::json::parse(text);
}

py::object to_python(const nlohmann::json& value) {
  return py::module_::import("json").attr("loads")(value.dump());
}

py::array_t<double> to_array(const std::vector<double>& values) {
  py::array_t<double> array(static_cast<py::ssize_t>(values.size()));
  std::copy(values.begin(), values.end(), array.mutable_data());
  return array;
}

py::dict to_python(const identify::ParameterSet& parameters) {
  py::dict out;
  for (const auto& [name, value] : parameters) out[py::str(name)] = value;
  return out;
}

py::dict to_python(const identify::CurveSet& curves) {
  py::dict out;
  for (const auto& [name, curve] : curves) out[py::str(name)] = py::cast(curve);
  return out;
}

void register_curves(py::module_& m) {
  py::class_<identify::Curve>(m, "Curve",
                              "One sampled curve. x and y are NumPy arrays (copies) in the units their labels name, "
                              "e.g. x_label 'volume_cm3', y_label 'pressure_MPa'.")
      .def_property_readonly("x", [](const identify::Curve& c) { return to_array(c.x); })
      .def_property_readonly("y", [](const identify::Curve& c) { return to_array(c.y); })
      .def_readonly("x_label", &identify::Curve::x_label)
      .def_readonly("y_label", &identify::Curve::y_label)
      .def("__len__", [](const identify::Curve& c) { return c.x.size(); })
      .def("__repr__", [](const identify::Curve& c) {
        return "<demfit.Curve " + c.y_label + " against " + c.x_label + ", " + std::to_string(c.x.size()) +
               " points>";
      });
}

}  // namespace demfit::python
