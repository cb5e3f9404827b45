#pragma once
// Internal helpers shared by rbf_network.cpp and rbf_kernel.cpp (not installed API).
#include "demfit/rbf_surrogate/rbf_network.hpp"

namespace demfit::rbf_surrogate::detail {

// Number of polynomial tail terms: 0, 1 or d+1.
int tail_terms(Tail tail, int dims);
// Tail basis p_k(x) evaluated at the rows of x (n×q): [1, x_1, ..., x_d].
MatrixXd tail_matrix(Tail tail, const MatrixXd& x);
// phi(r) - phi(0) when `shifted`, else phi(r). With a constant in the tail sum_i alpha_i = 0, so the
// shift changes only beta; it removes the large common part c of sqrt(r^2 + c^2) at wide widths, whose
// cancellation in sum_i alpha_i phi_i would otherwise cost several digits (flat-limit regime).
double kernel_value(Basis basis, double r, double width, bool shifted);
// Kernel matrix from squared distances.
MatrixXd kernel_from_squared_distances(Basis basis, const MatrixXd& d2, double width, bool shifted);
MatrixXd squared_distances(const MatrixXd& a, const MatrixXd& b);
// +1 when the kernel is (conditionally) positive definite on the tail's null space, -1 for the
// multiquadric (conditionally negative definite of order 1, Micchelli 1986). A ridge term is added as
// sign·lambda·I so that it regularises instead of cancelling the spectrum.
double definiteness_sign(Basis basis);
bool uses_width(Basis basis);
const char* basis_name(Basis basis);

}  // namespace demfit::rbf_surrogate::detail
