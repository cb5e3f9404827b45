#pragma once
// The parts of the demfit Python module (one file per concept) and the conversions they share.
#include <string>

#include <nlohmann/json.hpp>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>  // std::optional, std::vector and std::pair arguments and results
#include <pybind11/stl/filesystem.h>  // file arguments: str or os.PathLike

#include "demfit/identify/model.hpp"

namespace demfit::python {

namespace py = pybind11;

void register_errors(py::module_& m);    // demfit.Error, demfit.InputError (errors.cpp)
void register_curves(py::module_& m);    // demfit.Curve (convert.cpp)
void register_simulate(py::module_& m);  // demfit.simulate (simulate.cpp)
void register_study(py::module_& m);     // demfit.identify, resume, open_study, Study (study.cpp)
void register_diagnose(py::module_& m);  // demfit.diagnose (diagnose.cpp)
void register_imaging(py::module_& m);   // demfit.surface_profile (imaging.cpp)

// Throws std::invalid_argument (demfit.InputError in Python) with `message`.
[[noreturn]] void input_error(const std::string& message);

// A Python object (dict, list, str, number, bool, None) as JSON, through Python's json module;
// `field` names it in the error for anything else (NaN and infinity included).
nlohmann::json to_json(const py::handle& object, const std::string& field);
// JSON as the corresponding Python objects.
py::object to_python(const nlohmann::json& value);

py::array_t<double> to_array(const std::vector<double>& values);
py::dict to_python(const identify::ParameterSet& parameters);
py::dict to_python(const identify::CurveSet& curves);  // name -> demfit.Curve

}  // namespace demfit::python
