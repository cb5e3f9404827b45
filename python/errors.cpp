// Library errors as Python exceptions carrying the one-line message the command line prints after
// "demfit: error: ". Bad input (std::invalid_argument) is demfit.InputError, a ValueError; any
// other failure the library reports (std::runtime_error: unreadable files, failed simulations,
// refused output folders) is demfit.Error, a RuntimeError. InputError is also a demfit.Error.
#include <stdexcept>

#include "bindings.hpp"
#include "demfit/identify/safe_output.hpp"

namespace demfit::python {

namespace {
PyObject* error_type = nullptr;
PyObject* input_error_type = nullptr;
}  // namespace

void input_error(const std::string& message) { throw std::invalid_argument(message); }

void register_errors(py::module_& m) {
  error_type = PyErr_NewExceptionWithDoc("demfit.Error",
                                         "A demfit failure; str(error) is the command line's one-line message.",
                                         PyExc_RuntimeError, nullptr);
  if (!error_type) throw py::error_already_set();
  py::tuple bases = py::make_tuple(py::handle(error_type), py::handle(PyExc_ValueError));
  input_error_type = PyErr_NewExceptionWithDoc("demfit.InputError",
                                               "Bad input (a field, a value, an option), named in the message.",
                                               bases.ptr(), nullptr);
  if (!input_error_type) throw py::error_already_set();
  m.attr("Error") = py::handle(error_type);
  m.attr("InputError") = py::handle(input_error_type);
  py::register_exception_translator([](std::exception_ptr pending) {
    try {
      if (pending) std::rethrow_exception(pending);
    } catch (const py::builtin_exception&) {
      throw;  // pybind11's own (type, cast and key errors): its translator maps them
    } catch (const std::invalid_argument& e) {
      PyErr_SetString(input_error_type, identify::printable(e.what()).c_str());
    } catch (const std::runtime_error& e) {
      PyErr_SetString(error_type, identify::printable(e.what()).c_str());
    }
  });
}

}  // namespace demfit::python
