// Placeholders until the implicit integrators land (issue 3 work in progress):
// choosing them is refused with a clear message.
#include "implicit.hpp"

namespace vgd::sim::detail {
std::unique_ptr<Integrator> make_implicit_euler(const IntegratorSettings&) {
  throw SimulationError("implicit Euler is not available in this build yet");
}
std::unique_ptr<Integrator> make_bdf(const IntegratorSettings&) {
  throw SimulationError("the BDF (CVODE) integrator is not available in this build yet");
}
}  // namespace vgd::sim::detail
