#pragma once
// Bracketed root finding (GSL Brent) shared by the analytic references.
#include <functional>

namespace craterkit::test_support {

// Root of f in [lower, upper], where f(lower) and f(upper) differ in sign, to a relative tolerance of
// 1e-14. Throws std::runtime_error if it does not converge.
double brent_root(const std::function<double(double)>& f, double lower, double upper);

}  // namespace craterkit::test_support
