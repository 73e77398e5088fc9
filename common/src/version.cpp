#include "craterkit/common/version.hpp"

namespace craterkit {

const char* version() {
  return CRATERKIT_VERSION_STRING;
}

}  // namespace craterkit
