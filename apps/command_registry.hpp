#pragma once
// Self-registering subcommands. A command file defines
//   const bool scale_registered = craterkit::cli::register_command({"scale", 10, &add_scale_command});
// (named after its command: the command files are compiled together, apps/CMakeLists.txt, so the names they
// define outside a function must differ from file to file)
// where add_scale_command(CLI::App& parent) adds the subcommand, its options and its callback.
// Callbacks report bad user input by throwing craterkit::InputError (exit status 2, nothing written).
#include <CLI/CLI.hpp>
#include <vector>

namespace craterkit::cli {

struct CommandEntry {
  const char* name;
  int order;  // position in --help (small first)
  void (*add)(CLI::App& parent);
};

inline std::vector<CommandEntry>& command_registry() {
  static std::vector<CommandEntry> entries;
  return entries;
}

inline bool register_command(CommandEntry entry) {
  command_registry().push_back(entry);
  return true;
}

}  // namespace craterkit::cli
