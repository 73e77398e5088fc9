#pragma once
// The version of craterkit the libraries were built as (the project version of the top CMakeLists.txt), for
// the outputs that record which code made them (JSON, snapshots, the Python package).
namespace craterkit {

const char* version();

}  // namespace craterkit
