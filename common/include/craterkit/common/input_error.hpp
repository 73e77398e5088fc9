#pragma once
// The one exception type for bad user input (arguments, configuration keys, table cells).
// Its message names where the problem is (flag, key, or file:row:column), the offending value and
// what is allowed, so that the CLI can print it verbatim and exit with status 2.
#include <stdexcept>
#include <string>

namespace craterkit {

class InputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace craterkit
