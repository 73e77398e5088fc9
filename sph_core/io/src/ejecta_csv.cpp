#include "craterkit/sph/io/ejecta_csv.hpp"

#include <cstdio>

namespace craterkit::sph {

const char* ejecta_csv_header() {
  return "id,material,mass,time,step,x,y,z,vx,vy,vz";
}

std::string ejecta_csv_row(const EjectaRecord& r) {
  char row[512];
  std::snprintf(row, sizeof row, "%llu,%u,%.17g,%.17g,%llu,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g",
                static_cast<unsigned long long>(r.id), static_cast<unsigned>(r.material), r.mass, r.time,
                static_cast<unsigned long long>(r.step), r.x, r.y, r.z, r.vx, r.vy, r.vz);
  return row;
}

}  // namespace craterkit::sph
