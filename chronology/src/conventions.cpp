#include "craterkit/chronology/conventions.hpp"
