// The compiled part of the `demfit` Python package (python/demfit/__init__.py re-exports it).
#include "bindings.hpp"

PYBIND11_MODULE(_demfit, m) {
  m.doc() =
      "demfit: identify DEM contact parameters from measured curves. Case runs, studies (identify, "
      "resume, read), diagnoses and drum photos; SI units unless a curve label names its unit.";
  demfit::python::register_errors(m);
  demfit::python::register_curves(m);
  demfit::python::register_simulate(m);
  demfit::python::register_study(m);
  demfit::python::register_diagnose(m);
  demfit::python::register_imaging(m);
}
