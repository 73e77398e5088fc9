#include "craterkit/chronology/crater_counts.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <sstream>
#include <utility>

#include "craterkit/common/atomic_file.hpp"
#include "craterkit/common/format_number.hpp"
#include "craterkit/common/input_error.hpp"
#include "text_table.hpp"

namespace craterkit::chronology {
namespace {

using detail::lower;
using detail::parse_number;
using detail::split_fields;
using detail::trim;
using detail::where;

void add_crater(CraterCounts& c, double diameter, double fraction, const std::string& path,
                std::size_t line) {
  if (!(diameter > 0.0))
    throw InputError(where(path, line) + ": crater diameter " + format_number(diameter) + " must be > 0");
  if (!(fraction > 0.0 && (fraction <= 1.0 || c.buffered) && std::isfinite(fraction))) {
    throw InputError(where(path, line) + ": crater fraction " + format_number(fraction) +
                     " must be in (0, 1]");
  }
  c.diameters.push_back(diameter);
  c.fractions.push_back(fraction);
}

// "key = value [<unit>]" -> value (and the unit tag, without its brackets, when given), or nothing if the
// line is not that key.
bool key_value(const std::string& line, const std::string& key, std::string& value,
               std::string* unit = nullptr) {
  const auto eq = line.find('=');
  if (eq == std::string::npos) return false;
  if (lower(trim(line.substr(0, eq))) != lower(key)) return false;
  value = trim(line.substr(eq + 1));
  const auto open = value.find('<');
  if (open != std::string::npos) {
    const auto close = value.find('>', open);
    if (unit != nullptr)
      *unit = trim(value.substr(open + 1, close == std::string::npos ? std::string::npos : close - open - 1));
    value = trim(value.substr(0, open));
  }
  return true;
}

// Craterstats table "crater = {col1, col2, ..." : column names after the brace.
std::vector<std::string> brace_columns(const std::string& line) {
  const auto brace = line.find('{');
  std::vector<std::string> cols;
  std::stringstream ss(line.substr(brace + 1));
  std::string c;
  while (std::getline(ss, c, ',')) cols.push_back(lower(trim(c)));
  return cols;
}

// Shared reader of .diam and .scc: area key and the crater table in km.
CraterCounts read_craterstats(const std::string& path, const std::string& area_key) {
  const auto lines = detail::read_lines(path);
  CraterCounts c;
  c.source = path;
  bool have_area = false, have_table = false;
  for (std::size_t i = 0; i < lines.size(); ++i) {
    const std::string line = trim(lines[i]);
    if (line.empty() || line[0] == '#') continue;
    std::string value, unit;
    if (key_value(line, area_key, value, &unit)) {
      if (!unit.empty() && unit != "km^2" && unit != "km2") {
        throw InputError(where(path, i) + ": " + area_key + " = " + value + " <" + unit +
                         ">: the unit must be <km^2> (or no tag: km^2); convert the area to km^2");
      }
      const double km2 = parse_number(value, path, i, area_key);
      if (!(km2 > 0.0))
        throw InputError(where(path, i) + ": " + area_key + " = " + value + " km^2 must be > 0");
      c.area = km2 * 1e6;
      have_area = true;
      continue;
    }
    if (line.find('{') == std::string::npos) continue;
    const std::string name = lower(trim(line.substr(0, line.find('='))));
    const bool is_crater_table = name == "crater";
    const auto cols = brace_columns(line);
    int d_col = -1, f_col = -1, r_col = -1;
    for (std::size_t k = 0; k < cols.size(); ++k) {
      if (cols[k] == "diam" || cols[k] == "diameter") d_col = static_cast<int>(k);
      if (cols[k] == "fraction") f_col = static_cast<int>(k);
      if (cols[k] == "reference_area") r_col = static_cast<int>(k);
    }
    if (is_crater_table && d_col < 0) {
      throw InputError(where(path, i) + ": crater table has no 'diameter' (or 'diam') column");
    }
    if (is_crater_table && r_col >= 0) {
      // Buffered counting: each crater was counted on its own area; it stands for 1 km^2 / reference_area
      // craters on a nominal 1 km^2 (the file's area and fractions are not used).
      if (f_col >= 0) {
        throw InputError(where(path, i) +
                         ": crater table has both 'fraction' and 'reference_area'; give one");
      }
      c.buffered = true;
      f_col = r_col;
    }
    std::size_t j = i + 1;
    for (; j < lines.size(); ++j) {
      const std::string row = trim(lines[j]);
      if (row.empty() || row[0] == '#') continue;
      if (row[0] == '}') break;
      if (!is_crater_table) continue;
      const auto fields = split_fields(row);
      const int need = std::max(d_col, f_col) + 1;
      if (static_cast<int>(fields.size()) < need) {
        throw InputError(where(path, j) + ": expected at least " + std::to_string(need) + " columns, found " +
                         std::to_string(fields.size()));
      }
      const double d_km = parse_number(fields[static_cast<std::size_t>(d_col)], path, j,
                                       cols[static_cast<std::size_t>(d_col)]);
      double f = 1.0;
      if (f_col >= 0) {
        const char* column = c.buffered ? "reference_area" : "fraction";
        const double cell = parse_number(fields[static_cast<std::size_t>(f_col)], path, j, column);
        if (c.buffered && !(cell > 0.0)) {
          throw InputError(where(path, j) + ": reference_area " + format_number(cell) + " km^2 must be > 0");
        }
        f = c.buffered ? 1.0 / cell : cell;
      }
      add_crater(c, d_km * 1000.0, f, path, j);
    }
    if (j >= lines.size())
      throw InputError(where(path, i) + ": table '" + name + "' opened with '{' is never closed with '}'");
    if (is_crater_table) have_table = true;
    i = j;
  }
  if (c.buffered) {
    c.area = 1e6;  // the nominal 1 km^2 the weights refer to
    have_area = true;
  }
  if (!have_area) throw InputError(path + ": no '" + area_key + " = <km^2>' line found");
  if (!have_table) throw InputError(path + ": no 'crater = {diameter ...' table found");
  return c;
}

}  // namespace

void validate(const CraterCounts& c) {
  if (!(c.area > 0.0))
    throw InputError(c.source + ": counting area " + format_number(c.area) + " m^2 must be > 0");
  if (c.binned()) {
    for (std::size_t i = 0; i < c.bins.size(); ++i) {
      if (!(c.bins[i].diameter > 0.0) || !(c.bins[i].cumulative_count >= 0.0)) {
        throw InputError(c.source + ": bin " + std::to_string(i + 1) + " needs diameter > 0 and count >= 0");
      }
      if (i > 0 && (!(c.bins[i].diameter > c.bins[i - 1].diameter) ||
                    c.bins[i].cumulative_count > c.bins[i - 1].cumulative_count)) {
        throw InputError(c.source + ": bin " + std::to_string(i + 1) +
                         ": diameters must increase and cumulative counts must not increase");
      }
    }
  } else if (c.diameters.size() != c.fractions.size()) {
    throw InputError(c.source + ": every crater needs a fraction");
  }
}

CraterCounts read_crater_csv(const std::string& path) {
  const auto lines = detail::read_lines(path);
  CraterCounts c;
  c.source = path;
  bool have_area = false, have_header = false;
  int d_col = -1, f_col = -1, n_col = -1;
  double unit = 1.0;
  for (std::size_t i = 0; i < lines.size(); ++i) {
    const std::string line = trim(lines[i]);
    if (line.empty()) continue;
    if (line[0] == '#') {
      std::string value;
      const std::string body = trim(line.substr(1));
      if (key_value(body, "buffered", value)) {
        // "# buffered = true": fractions are 1 km^2 / reference area and may exceed 1 (written by craterkit).
        if (value != "true" && value != "false")
          throw InputError(where(path, i) + ": buffered = " + value + " is not allowed: true or false");
        c.buffered = value == "true";
        continue;
      }
      if (key_value(body, "area_km2", value) || key_value(body, "area_m2", value)) {
        const bool km = lower(body).rfind("area_km2", 0) == 0;
        const double a = parse_number(value, path, i, km ? "area_km2" : "area_m2");
        if (!(a > 0.0)) throw InputError(where(path, i) + ": area = " + value + " must be > 0");
        c.area = km ? a * 1e6 : a;
        have_area = true;
      }
      continue;
    }
    const auto fields = split_fields(line);
    if (!have_header) {
      for (std::size_t k = 0; k < fields.size(); ++k) {
        const std::string f = lower(fields[k]);
        if (f == "diameter_m") d_col = static_cast<int>(k), unit = 1.0;
        if (f == "diameter_km") d_col = static_cast<int>(k), unit = 1000.0;
        if (f == "fraction") f_col = static_cast<int>(k);
        if (f == "cumulative_count") n_col = static_cast<int>(k);
      }
      if (d_col < 0) {
        throw InputError(where(path, i) +
                         ": header must name a 'diameter_m' or 'diameter_km' column (found '" + line + "')");
      }
      have_header = true;
      continue;
    }
    const int need = std::max({d_col, f_col, n_col}) + 1;
    if (static_cast<int>(fields.size()) < need) {
      throw InputError(where(path, i) + ": expected at least " + std::to_string(need) + " columns, found " +
                       std::to_string(fields.size()));
    }
    const double d = parse_number(fields[static_cast<std::size_t>(d_col)], path, i, "diameter") * unit;
    if (n_col >= 0) {
      const double n = parse_number(fields[static_cast<std::size_t>(n_col)], path, i, "cumulative_count");
      if (!(d > 0.0) || !(n >= 0.0))
        throw InputError(where(path, i) + ": diameter must be > 0 and cumulative_count >= 0");
      if (!c.bins.empty() && (!(d > c.bins.back().diameter) || n > c.bins.back().cumulative_count)) {
        throw InputError(where(path, i) +
                         ": bins must have increasing diameters and non-increasing cumulative counts");
      }
      c.bins.push_back({d, n});
    } else {
      const double f =
          f_col >= 0 ? parse_number(fields[static_cast<std::size_t>(f_col)], path, i, "fraction") : 1.0;
      add_crater(c, d, f, path, i);
    }
  }
  if (!have_header) throw InputError(path + ": no header line with a 'diameter_m' or 'diameter_km' column");
  if (!have_area)
    throw InputError(path + ": no counting area; add a comment line '# area_km2 = X' or '# area_m2 = X'");
  return c;
}

CraterCounts read_craterstats_binned(const std::string& path) {
  const auto lines = detail::read_lines(path);
  CraterCounts c;
  c.source = path;
  bool have_area = false, have_table = false;
  std::vector<std::pair<double, double>> bins;  // (D_min in m, craters in the bin)
  for (std::size_t i = 0; i < lines.size(); ++i) {
    const std::string line = trim(lines[i]);
    if (line.empty() || line[0] == '#') continue;
    std::string value;
    if (key_value(line, "area", value)) {
      const double km2 = parse_number(value, path, i, "area");
      if (!(km2 > 0.0)) throw InputError(where(path, i) + ": area = " + value + " km^2 must be > 0");
      c.area = km2 * 1e6;
      have_area = true;
      continue;
    }
    if (line.find('{') == std::string::npos) continue;
    const std::string name = lower(trim(line.substr(0, line.find('='))));
    const auto cols = brace_columns(line);
    const bool is_table = name == "table";
    if (is_table && (cols.size() != 2 || cols[0] != "diameter" || cols[1] != "frequency")) {
      throw InputError(where(path, i) +
                       ": the binned table must be 'table = {diameter,frequency' (diameter in km, "
                       "craters per bin); other columns (event_frequency) are not supported");
    }
    std::size_t j = i + 1;
    for (; j < lines.size(); ++j) {
      const std::string row = trim(lines[j]);
      if (row.empty() || row[0] == '#') continue;
      if (row[0] == '}') break;
      if (!is_table) continue;
      const auto fields = split_fields(row);
      if (fields.size() != 2) {
        throw InputError(where(path, j) + ": expected 2 columns (diameter, frequency), found " +
                         std::to_string(fields.size()));
      }
      const double d_km = parse_number(fields[0], path, j, "diameter");
      const double n = parse_number(fields[1], path, j, "frequency");
      if (!(d_km > 0.0) || !(n >= 0.0)) {
        throw InputError(where(path, j) + ": diameter must be > 0 km and frequency >= 0 (found " + fields[0] +
                         ", " + fields[1] + ")");
      }
      bins.emplace_back(d_km * 1000.0, n);
    }
    if (j >= lines.size())
      throw InputError(where(path, i) + ": table '" + name + "' opened with '{' is never closed with '}'");
    if (is_table) have_table = true;
    i = j;
  }
  if (!have_area) throw InputError(path + ": no 'area = <km^2>' line found");
  if (!have_table || bins.empty()) throw InputError(path + ": no 'table = {diameter,frequency' rows found");
  // Bins may be listed in any order; craters with D >= D_j are the sum over the bins from D_j up.
  std::sort(bins.begin(), bins.end());
  double cumulative = 0.0;
  c.bins.resize(bins.size());
  for (std::size_t k = bins.size(); k-- > 0;) {
    cumulative += bins[k].second;
    c.bins[k] = {bins[k].first, cumulative};
  }
  for (std::size_t k = 1; k < c.bins.size(); ++k) {
    if (c.bins[k].diameter == c.bins[k - 1].diameter)
      throw InputError(path + ": bin diameter " + format_number(c.bins[k].diameter / 1000.0) +
                       " km is listed twice");
  }
  return c;
}

CraterCounts read_craterstats_stat(const std::string& path) {
  const auto lines = detail::read_lines(path);
  CraterCounts c;
  c.source = path;
  std::optional<double> header_area_km2;
  std::optional<double> derived_area_km2;
  std::size_t columns = 0;
  for (std::size_t i = 0; i < lines.size(); ++i) {
    const std::string line = trim(lines[i]);
    if (line.empty()) continue;
    if (line[0] == '#') {
      // "#Area :  340.856149328  qkm , ..." (CraterTools); the area is otherwise derived as craterstats does.
      const std::string body = trim(line.substr(1));
      if (lower(body).rfind("area", 0) == 0 && body.find(':') != std::string::npos) {
        std::stringstream rest(body.substr(body.find(':') + 1));
        std::string number;
        rest >> number;
        header_area_km2 = parse_number(number, path, i, "Area");
      }
      continue;
    }
    const auto fields = split_fields(line);
    if (columns == 0) columns = fields.size();
    if ((fields.size() != 7 && fields.size() != 11) || fields.size() != columns) {
      throw InputError(where(path, i) +
                       ": a .stat row has 7 or 11 columns (D, N, N density, error, cumulative N, "
                       "cumulative density, error[, ...]), the same in every row; found " +
                       std::to_string(fields.size()));
    }
    const double d_km = parse_number(fields[0], path, i, "D");
    const double cumulative = parse_number(fields[4], path, i, "C(D)");
    const double density = parse_number(fields[5], path, i, "N_cum");
    if (!(d_km > 0.0) || !(cumulative >= 0.0)) {
      throw InputError(where(path, i) + ": D must be > 0 km and the cumulative count C(D) >= 0 (found " +
                       fields[0] + ", " + fields[4] + ")");
    }
    if (!derived_area_km2 && cumulative > 0.0 && density > 0.0) derived_area_km2 = cumulative / density;
    c.bins.push_back({d_km * 1000.0, cumulative});
  }
  if (c.bins.empty()) throw InputError(path + ": no rows of numbers found");
  const auto area = header_area_km2 ? header_area_km2 : derived_area_km2;
  if (!area || !(*area > 0.0)) {
    throw InputError(path +
                     ": no counting area: neither an '#Area : X qkm' line nor a row with a cumulative count "
                     "and density");
  }
  c.area = *area * 1e6;
  return c;
}

CraterCounts read_craterstats_diam(const std::string& path) {
  return read_craterstats(path, "area");
}
CraterCounts read_crater_tools_scc(const std::string& path) {
  return read_craterstats(path, "Total_area");
}

CraterCounts read_crater_counts(const std::string& path) {
  if (!std::filesystem::exists(path)) throw InputError("crater count file '" + path + "' does not exist");
  const std::string ext = lower(std::filesystem::path(path).extension().string());
  CraterCounts c;
  if (ext == ".csv")
    c = read_crater_csv(path);
  else if (ext == ".diam")
    c = read_craterstats_diam(path);
  else if (ext == ".scc")
    c = read_crater_tools_scc(path);
  else if (ext == ".binned")
    c = read_craterstats_binned(path);
  else if (ext == ".stat")
    c = read_craterstats_stat(path);
  else
    throw InputError("crater count file '" + path + "': extension '" + ext +
                     "' is not known; allowed: .csv, .diam, .scc, .binned, .stat");
  validate(c);
  return c;
}

namespace {
std::string exact(double value) {
  char buffer[40];
  std::snprintf(buffer, sizeof buffer, "%.17g", value);
  return buffer;
}
}  // namespace

std::string format_crater_csv(const CraterCounts& counts) {
  validate(counts);
  std::ostringstream out;
  out << "# crater counts written by craterkit";
  if (!counts.source.empty()) out << " from " << counts.source;
  out << "\n# area_m2 = " << exact(counts.area) << "\n";
  if (counts.buffered) out << "# buffered = true\n";
  if (counts.binned()) {
    out << "diameter_m,cumulative_count\n";
    for (const auto& bin : counts.bins)
      out << exact(bin.diameter) << "," << exact(bin.cumulative_count) << "\n";
  } else {
    out << "diameter_m,fraction\n";
    for (std::size_t i = 0; i < counts.diameters.size(); ++i)
      out << exact(counts.diameters[i]) << "," << exact(counts.fractions[i]) << "\n";
  }
  return out.str();
}

void write_crater_csv(const CraterCounts& counts, const std::string& path) {
  write_text_atomically(path, format_crater_csv(counts));
}

std::string format_craterstats(const CraterCounts& counts, const std::string& extension) {
  validate(counts);
  const std::string ext = lower(extension);
  std::ostringstream out;
  out << "# crater counts written by craterkit";
  if (!counts.source.empty()) out << " from " << counts.source;
  out << "\n# diameters in km, areas in km^2\n";
  if (ext == ".binned") {
    if (!counts.binned())
      throw InputError("counts of single craters cannot be written as .binned: write .diam");
    out << "area = " << exact(counts.area * 1e-6) << "\n\ntable = {diameter,frequency\n";
    for (std::size_t k = 0; k < counts.bins.size(); ++k) {
      const double above = k + 1 < counts.bins.size() ? counts.bins[k + 1].cumulative_count : 0.0;
      out << exact(counts.bins[k].diameter * 1e-3) << "\t" << exact(counts.bins[k].cumulative_count - above)
          << "\n";
    }
    out << "}\n";
    return out.str();
  }
  if (ext != ".diam" && ext != ".scc") {
    throw InputError("crater count file extension '" + extension +
                     "' cannot be written; allowed: .csv, .diam, .scc, "
                     ".binned");
  }
  if (counts.binned())
    throw InputError("binned counts cannot be written as " + ext + ": write .binned or .csv");
  if (counts.buffered) {
    if (ext != ".diam")
      throw InputError("buffered counts (reference areas) can only be written as .diam or .csv");
    out << "crater = {diameter, reference_area\n";
    for (std::size_t i = 0; i < counts.diameters.size(); ++i)
      out << exact(counts.diameters[i] * 1e-3) << "\t" << exact(counts.area * 1e-6 / counts.fractions[i])
          << "\n";
    out << "}\n";
    return out.str();
  }
  out << (ext == ".scc" ? "Total_area = " + exact(counts.area * 1e-6) + " <km^2>\n"
                        : "area = " + exact(counts.area * 1e-6) + "\n");
  out << (ext == ".scc" ? "crater = {diam, fraction\n" : "crater = {diameter, fraction\n");
  for (std::size_t i = 0; i < counts.diameters.size(); ++i)
    out << exact(counts.diameters[i] * 1e-3) << "\t" << exact(counts.fractions[i]) << "\n";
  out << "}\n";
  return out.str();
}

void write_crater_counts(const CraterCounts& counts, const std::string& path) {
  const std::string ext = lower(std::filesystem::path(path).extension().string());
  write_text_atomically(path, ext == ".csv" ? format_crater_csv(counts) : format_craterstats(counts, ext));
}

}  // namespace craterkit::chronology
