// craterkit: command-line entry point. Exit status: 0 success, 2 bad arguments or input (the message
// names the flag, key or table cell, the value and what is allowed), 1 any other failure.
#include <algorithm>
#include <exception>
#include <iostream>

#include <CLI/CLI.hpp>

#include "command_registry.hpp"
#include "craterkit/common/input_error.hpp"
#include "craterkit_version.hpp"

int main(int argc, char** argv) {
  CLI::App app{"craterkit: impact cratering on small, low-gravity asteroids (SPH, scaling, chronology)",
               "craterkit"};
  app.set_version_flag("--version", std::string("craterkit ") + CRATERKIT_VERSION);
  app.require_subcommand(1);
  app.fallthrough(false);

  auto entries = craterkit::cli::command_registry();
  std::sort(entries.begin(), entries.end(), [](const auto& a, const auto& b) { return a.order < b.order; });
  for (const auto& entry : entries) entry.add(app);

  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    std::cerr << "craterkit: error: " << e.what() << "\n";
    std::cerr << "Run with --help for usage.\n";
    return 2;
  } catch (const craterkit::InputError& e) {
    std::cerr << "craterkit: error: " << e.what() << "\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "craterkit: failed: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
