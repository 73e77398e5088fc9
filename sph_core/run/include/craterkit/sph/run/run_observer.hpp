#pragma once
// Something that watches a run and acts around its steps: writes a log or snapshots, reports progress,
// decides that the run is over (the end of crater growth). run_simulation() calls every observer in the
// order given, after each step and before the step's checkpoint, so that whatever an observer writes for
// a step is on disk before a checkpoint of that step can exist: a run killed at any moment and resumed
// repeats exactly what the uninterrupted run does.
#include <limits>

#include "craterkit/sph/io/snapshot.hpp"
#include "craterkit/sph/solver/simulation.hpp"

namespace craterkit::sph {

class RunObserver {
 public:
  virtual ~RunObserver() = default;

  // Before the first step. checkpoint: null for a new run at t = 0; for a run continued from a checkpoint,
  // its attributes (with what save() put there). Returns true if the run is already over (no step is
  // taken; finish() still runs).
  virtual bool start(Simulation& simulation, const RunAttributes* checkpoint) {
    (void)simulation;
    (void)checkpoint;
    return false;
  }

  // After each step. Returns true to end the run after this step.
  virtual bool after_step(Simulation& simulation) {
    (void)simulation;
    return false;
  }

  // The next simulated time a step must end on exactly (an output time); infinity: none.
  [[nodiscard]] virtual double next_landing_time() const { return std::numeric_limits<double>::infinity(); }

  // Adds what the observer needs to resume to the attributes of a checkpoint.
  virtual void save(RunAttributes& checkpoint) const { (void)checkpoint; }

  // Once, after the last step.
  virtual void finish(Simulation& simulation) { (void)simulation; }
};

}  // namespace craterkit::sph
