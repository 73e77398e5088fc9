#include "support/root_finding.hpp"

#include <gsl/gsl_errno.h>
#include <gsl/gsl_roots.h>
#include <memory>
#include <stdexcept>

namespace craterkit::test_support {
namespace {

double call(double x, void* params) {
  return (*static_cast<const std::function<double(double)>*>(params))(x);
}

}  // namespace

double brent_root(const std::function<double(double)>& f, double lower, double upper) {
  gsl_function function{&call, const_cast<std::function<double(double)>*>(&f)};
  std::unique_ptr<gsl_root_fsolver, decltype(&gsl_root_fsolver_free)> solver(
      gsl_root_fsolver_alloc(gsl_root_fsolver_brent), &gsl_root_fsolver_free);
  gsl_root_fsolver_set(solver.get(), &function, lower, upper);
  for (int iteration = 0; iteration < 300; ++iteration) {
    gsl_root_fsolver_iterate(solver.get());
    const double lo = gsl_root_fsolver_x_lower(solver.get());
    const double hi = gsl_root_fsolver_x_upper(solver.get());
    if (gsl_root_test_interval(lo, hi, 0.0, 1e-14) == GSL_SUCCESS) return gsl_root_fsolver_root(solver.get());
  }
  throw std::runtime_error("Brent root finding did not converge");
}

}  // namespace craterkit::test_support
