#pragma once
// Factories of the implicit integrators. Implicit Euler lives in
// implicit_euler.cpp; the SUNDIALS CVODE adapter (bdf) in cvode.cpp, the only
// file that sees SUNDIALS headers.
#include <memory>

#include "vgd/sim/integrator.hpp"

namespace vgd::sim::detail {
std::unique_ptr<Integrator> make_implicit_euler(const IntegratorSettings& s);
std::unique_ptr<Integrator> make_bdf(const IntegratorSettings& s);
}  // namespace vgd::sim::detail
