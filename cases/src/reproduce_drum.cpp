#include <stdexcept>
#include "demfit/cases/reproduce.hpp"
namespace demfit::cases {
std::string reproduce_figures(const ReproduceOptions&) { throw std::runtime_error("figures: not yet"); }
std::string reproduce_table3(const ReproduceOptions&) { throw std::runtime_error("table3: not yet"); }
}
