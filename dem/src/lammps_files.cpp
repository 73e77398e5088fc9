#include "craterkit/dem/lammps_files.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <fstream>
#include <numbers>
#include <stdexcept>
#include <string>

#include "craterkit/common/atomic_file.hpp"

namespace craterkit::dem {

void write_lammps_data(const std::filesystem::path& path, const Grains& grains, const Box& box,
                       std::span<const int> types) {
  if (!types.empty() && types.size() != grains.size())
    throw std::invalid_argument(
        fmt::format("write_lammps_data: {} types for {} grains", types.size(), grains.size()));
  const int type_count = types.empty() ? 1 : *std::max_element(types.begin(), types.end());
  if (!types.empty() && *std::min_element(types.begin(), types.end()) < 1)
    throw std::invalid_argument("write_lammps_data: atom types start at 1");
  write_atomically(path, [&](const std::filesystem::path& tmp) {
    std::ofstream out(tmp);
    out << "craterkit grains (atom_style sphere: id type diameter density x y z)\n\n";
    out << grains.size() << " atoms\n" << type_count << " atom types\n\n";
    out << fmt::format("{:.17g} {:.17g} xlo xhi\n{:.17g} {:.17g} ylo yhi\n{:.17g} {:.17g} zlo zhi\n\n",
                       box.x_low, box.x_high, box.y_low, box.y_high, box.z_low, box.z_high);
    out << "Atoms # sphere\n\n";
    for (std::size_t i = 0; i < grains.size(); ++i)
      out << fmt::format("{} {} {:.17g} {:.17g} {:.17g} {:.17g} {:.17g} 0 0 0\n", i + 1,
                         types.empty() ? 1 : types[i], grains.diameter[i], grains.density[i], grains.x[i],
                         grains.y[i], grains.z[i]);
    out << "\nVelocities\n\n";
    for (std::size_t i = 0; i < grains.size(); ++i)
      out << fmt::format("{} {:.17g} {:.17g} {:.17g} {:.17g} {:.17g} {:.17g}\n", i + 1, grains.vx[i],
                         grains.vy[i], grains.vz[i], grains.omega_x[i], grains.omega_y[i], grains.omega_z[i]);
    out.flush();
    if (!out) throw std::runtime_error("write failed");
  });
}

Grains read_lammps_dump(const std::filesystem::path& path, std::vector<long>* ids) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error(fmt::format("{}: cannot open the LAMMPS dump", path.string()));
  auto fail = [&](std::size_t line, const std::string& what) {
    return std::runtime_error(
        fmt::format("{}:{}: not a craterkit grain dump: {}", path.string(), line, what));
  };
  std::string line;
  std::size_t line_number = 0;
  std::size_t atoms = 0;
  bool have_count = false;
  while (std::getline(in, line)) {
    ++line_number;
    if (line.rfind("ITEM: NUMBER OF ATOMS", 0) == 0) {
      if (!(in >> atoms)) throw fail(line_number + 1, "no atom count");
      have_count = true;
    } else if (line.rfind("ITEM: ATOMS", 0) == 0) {
      if (line.substr(12) != dump_columns)
        throw fail(line_number,
                   "columns '" + line.substr(12) + "', expected '" + std::string(dump_columns) + "'");
      break;
    }
  }
  if (!have_count || line.rfind("ITEM: ATOMS", 0) != 0) throw fail(line_number, "no ITEM: ATOMS section");
  Grains grains;
  if (ids) ids->clear();
  for (std::size_t i = 0; i < atoms; ++i) {
    long id = 0;
    double d = 0, m = 0, x = 0, y = 0, z = 0, vx = 0, vy = 0, vz = 0, wx = 0, wy = 0, wz = 0;
    if (!(in >> id >> d >> m >> x >> y >> z >> vx >> vy >> vz >> wx >> wy >> wz))
      throw fail(line_number + 1 + i, fmt::format("atom {} of {} missing or unreadable", i + 1, atoms));
    const double density = m / (std::numbers::pi * d * d * d / 6.0);
    grains.add(x, y, z, d, density);
    if (ids) ids->push_back(id);
    grains.vx.back() = vx;
    grains.vy.back() = vy;
    grains.vz.back() = vz;
    grains.omega_x.back() = wx;
    grains.omega_y.back() = wy;
    grains.omega_z.back() = wz;
  }
  return grains;
}

}  // namespace craterkit::dem
