// craterkit: command-line entry point. Exit status: 0 success, 2 bad arguments or input (the message
// names the flag, key or table cell, the value and what is allowed), 1 any other failure.
#include <algorithm>
#include <chrono>
#include <exception>
#include <iostream>
#include <thread>

#include <CLI/CLI.hpp>

#include "command_registry.hpp"
#include "craterkit/common/input_error.hpp"
#include "craterkit_version.hpp"
#include "processes.hpp"

int main(int argc, char** argv) {
  const craterkit::cli::Processes processes(argc, argv);  // MPI, when started by mpirun
  using craterkit::cli::Processes;
  // Over several processes a bad input is normally everyone's (each read the same files): process 0 says it
  // and ends the job, the others wait for that. Any other failure may be one process's alone, while the
  // others wait for it in a collective call: it says so with its rank and ends the whole job.
  const auto failed = [](int status, const char* what, const std::exception& e) {
    const bool several = Processes::count() > 1;
    if (status == 2 && several && Processes::rank() != 0)
      std::this_thread::sleep_for(std::chrono::seconds(2));  // still here: the input was bad here alone
    std::cerr << "craterkit: " << what;
    if (several && (status != 2 || Processes::rank() != 0))
      std::cerr << " (process " << Processes::rank() << " of " << Processes::count() << ")";
    std::cerr << ": " << e.what() << "\n";
    std::cerr.flush();
    Processes::end_all_if_several(status);
    return status;
  };
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
    return failed(2, "error", e);
  } catch (const std::exception& e) {
    return failed(1, "failed", e);
  }
  return 0;
}
