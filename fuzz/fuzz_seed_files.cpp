// Writes the seed particle files of fuzz_particle_file into the folder given: a checkpoint and a snapshot of
// a few particles with the integrity record, and a checkpoint without it (as earlier versions wrote them,
// which reaches the HDF5 library itself).
#include <cstdio>
#include <filesystem>

#include "craterkit/sph/io/checkpoint.hpp"
#include "craterkit/sph/io/snapshot.hpp"
#include "snapshot_hdf5.hpp"

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: fuzz_seed_files DIR\n");
    return 2;
  }
  namespace sph = craterkit::sph;
  const std::filesystem::path dir(argv[1]);
  std::filesystem::create_directories(dir);
  sph::Particles p;
  p.solid_fields = true;
  p.resize(3);
  p.for_each_field([](std::string_view, auto& field) {
    for (std::size_t i = 0; i < field.size(); ++i)
      field[i] = static_cast<std::decay_t<decltype(field[i])>>(i + 1);
  });
  sph::RunAttributes a;
  a.time = 0.5;
  a.step = 7;
  a.numbers["next_time_step"] = 1e-3;
  a.texts["setup"] = "impact";
  sph::write_checkpoint(dir / "checkpoint.h5", p, a);
  sph::write_snapshot(dir / "snapshot.h5", p, a);
  sph::detail::ParticleFileOptions legacy{sph::detail::kind_checkpoint, false};
  legacy.integrity_record = false;
  sph::detail::write_particle_file(dir / "legacy.h5", p, a, legacy);
  std::filesystem::remove(dir / "snapshot.xdmf");
  return 0;
}
