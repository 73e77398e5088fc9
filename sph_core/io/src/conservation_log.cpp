#include "craterkit/sph/io/conservation_log.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "craterkit/common/atomic_file.hpp"
#include "craterkit/common/input_error.hpp"

namespace craterkit::sph {
namespace {

// Neumaier's compensated sum: the error of each addition is carried separately, so sums of many
// terms of mixed sign (momenta) keep their round-off near one ulp of the largest partial sum.
struct CompensatedSum {
  double sum = 0;
  double compensation = 0;
  void add(double term) {
    const double t = sum + term;
    compensation += std::abs(sum) >= std::abs(term) ? (sum - t) + term : (term - t) + sum;
    sum = t;
  }
  [[nodiscard]] double value() const { return sum + compensation; }
};

constexpr int n_sums = 8;  // mass, px, py, pz, kinetic, internal, potential, |p|

// Block size of the partial sums: fixed (not derived from the thread count), so that the order of
// every addition, and therefore the result, is the same for any number of threads.
constexpr std::size_t block_size = 4096;

}  // namespace

ConservedQuantities measure_conserved(const Particles& p, std::array<double, 3> gravity) {
  const std::size_t n = p.size();
  const std::size_t n_blocks = (n + block_size - 1) / block_size;
  std::vector<std::array<double, n_sums>> blocks(n_blocks);

#pragma omp parallel for schedule(static)
  for (std::size_t b = 0; b < n_blocks; ++b) {
    std::array<CompensatedSum, n_sums> s{};
    const std::size_t end = std::min(n, (b + 1) * block_size);
    for (std::size_t i = b * block_size; i < end; ++i) {
      const double m = p.mass[i];
      const double v2 = p.vx[i] * p.vx[i] + p.vy[i] * p.vy[i] + p.vz[i] * p.vz[i];
      s[0].add(m);
      s[1].add(m * p.vx[i]);
      s[2].add(m * p.vy[i]);
      s[3].add(m * p.vz[i]);
      s[4].add(0.5 * m * v2);
      s[5].add(m * p.specific_energy[i]);
      // Potential of a uniform field: phi = -g.x, zero at the coordinate origin.
      s[6].add(-m * (gravity[0] * p.x[i] + gravity[1] * p.y[i] + gravity[2] * p.z[i]));
      s[7].add(m * std::sqrt(v2));
    }
    for (int k = 0; k < n_sums; ++k) blocks[b][k] = s[k].value();
  }

  std::array<CompensatedSum, n_sums> total{};
  for (const auto& block : blocks) {
    for (int k = 0; k < n_sums; ++k) total[k].add(block[k]);
  }
  ConservedQuantities q;
  q.mass = total[0].value();
  q.momentum_x = total[1].value();
  q.momentum_y = total[2].value();
  q.momentum_z = total[3].value();
  q.kinetic_energy = total[4].value();
  q.internal_energy = total[5].value();
  q.potential_energy = total[6].value();
  q.absolute_momentum = total[7].value();
  q.total_energy = q.kinetic_energy + q.internal_energy + q.potential_energy;
  return q;
}

double relative_energy_error(const ConservedQuantities& initial, const ConservedQuantities& now) {
  double scale = std::abs(initial.total_energy);
  if (scale == 0) {
    scale = std::abs(initial.kinetic_energy) + std::abs(initial.internal_energy) +
            std::abs(initial.potential_energy);
  }
  const double change = std::abs(now.total_energy - initial.total_energy);
  return scale > 0 ? change / scale : change;
}

double relative_momentum_error(const ConservedQuantities& initial, const ConservedQuantities& now) {
  const double scale = std::max(initial.absolute_momentum, now.absolute_momentum);
  if (scale == 0) return 0;
  const double dx = now.momentum_x - initial.momentum_x;
  const double dy = now.momentum_y - initial.momentum_y;
  const double dz = now.momentum_z - initial.momentum_z;
  return std::sqrt(dx * dx + dy * dy + dz * dz) / scale;
}

// ---- CSV log ---------------------------------------------------------------------------------

namespace {

constexpr int n_columns = 11;

std::string format_row(const ConservedQuantities& q) {
  char row[512];
  std::snprintf(row, sizeof row, "%.17g,%llu,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g\n", q.time,
                static_cast<unsigned long long>(q.step), q.mass, q.momentum_x, q.momentum_y, q.momentum_z,
                q.kinetic_energy, q.internal_energy, q.potential_energy, q.total_energy, q.absolute_momentum);
  return row;
}

std::vector<std::string> split_columns(const std::string& line) {
  std::vector<std::string> columns;
  std::string column;
  std::istringstream in(line);
  while (std::getline(in, column, ',')) columns.push_back(column);
  if (!line.empty() && line.back() == ',') columns.emplace_back();
  return columns;
}

// True if `text` is a complete non-negative decimal integer; its value in *value.
bool parse_step(const std::string& text, std::uint64_t* value) {
  if (text.empty() || text.find_first_not_of("0123456789") != std::string::npos) return false;
  try {
    *value = std::stoull(text);
  } catch (const std::exception&) {
    return false;
  }
  return true;
}

}  // namespace

const char* ConservationLog::header() {
  return "time,step,mass,momentum_x,momentum_y,momentum_z,kinetic_energy,internal_energy,potential_energy,"
         "total_energy,absolute_momentum";
}

ConservationLog::ConservationLog(const std::filesystem::path& csv) : path_(csv) {
  out_.open(path_, std::ios::binary | std::ios::trunc);
  if (!out_) throw std::runtime_error("cannot open conservation log " + path_.string() + " for writing");
  out_ << header() << '\n';
  out_.flush();
}

ConservationLog::ConservationLog(const std::filesystem::path& csv, std::uint64_t restart_step) : path_(csv) {
  std::error_code ec;
  if (!std::filesystem::exists(path_, ec)) {
    *this = ConservationLog(csv);  // nothing to resume: a new log
    return;
  }
  std::ifstream in(path_, std::ios::binary);
  if (!in) throw std::runtime_error("cannot open conservation log " + path_.string() + " to resume it");
  std::string line;
  if (!std::getline(in, line) || line != header()) {
    throw InputError(
        "conservation log " + path_.string() + ": the header is not '" + std::string(header()) +
        "', so it was not written by this version of craterkit; move it away to start a new log");
  }
  std::string kept = line + '\n';
  std::size_t row = 1;
  while (std::getline(in, line)) {
    ++row;
    // A killed run can leave a last line without its newline: it is after the checkpoint, drop it.
    if (in.eof()) break;
    const auto columns = split_columns(line);
    std::uint64_t step = 0;
    if (columns.size() != n_columns || !parse_step(columns[1], &step)) {
      throw InputError("conservation log " + path_.string() + " row " + std::to_string(row) + ": '" + line +
                       "' is not a row of " + std::to_string(n_columns) + " columns with an integer step");
    }
    if (step > restart_step) break;  // rows are in step order: the rest is after the checkpoint
    kept += line + '\n';
  }
  in.close();
  write_text_atomically(path_, kept);
  out_.open(path_, std::ios::binary | std::ios::app);
  if (!out_) throw std::runtime_error("cannot open conservation log " + path_.string() + " for appending");
}

void ConservationLog::append(const ConservedQuantities& q) {
  out_ << format_row(q);
  out_.flush();
  if (!out_) throw std::runtime_error("cannot write to conservation log " + path_.string());
}

}  // namespace craterkit::sph
