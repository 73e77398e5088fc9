#pragma once
// Crater counts of a surface unit: rim-to-rim diameters with the counting area, or binned cumulative
// counts. Readers for the formats crater-counting tools write; every error names file:line.
//
//  .csv   comment lines start with '#'; the area is given in a comment "# area_km2 = X" or "# area_m2 = X".
//         Unbinned: header with 'diameter_m' or 'diameter_km' (optional 'fraction'; other columns ignored).
//         Binned:   header with 'diameter_m' or 'diameter_km' and 'cumulative_count' (N(>=D) per row).
//  .diam  craterstats: "area = X" (km^2), then "crater = {diameter[, fraction, lon, lat]" rows (km) up to
//  "}". .scc   CraterTools / craterstats spatial count: "Total_area = X <km^2>", then
//         "crater = {diam, fraction, lon, lat, ...}" rows (km); other {...} blocks are skipped.
// A crater's fraction (buffered counting, 0 < f <= 1) weights it in the fits.
#include <string>
#include <vector>

namespace craterkit::chronology {

struct CumulativeBin {
  double diameter = 0.0;          // m
  double cumulative_count = 0.0;  // craters with D >= diameter in the area
};

struct CraterCounts {
  std::string source;               // file name or description
  double area = 0.0;                // m^2
  std::vector<double> diameters;    // m (unbinned)
  std::vector<double> fractions;    // same size as diameters
  std::vector<CumulativeBin> bins;  // binned cumulative counts (diameter increasing)
  bool binned() const { return !bins.empty(); }
};

void validate(const CraterCounts& counts);

CraterCounts read_crater_counts(const std::string& path);  // by extension: .csv, .diam, .scc
CraterCounts read_crater_csv(const std::string& path);
CraterCounts read_craterstats_diam(const std::string& path);
CraterCounts read_crater_tools_scc(const std::string& path);

// The counts as a craterkit .csv (the format read_crater_csv reads back exactly): '#' comment lines with
// the source and "area_m2 = X", then diameter_m,fraction (unbinned) or diameter_m,cumulative_count
// (binned), every number with 17 significant digits. Validates the counts first (InputError).
std::string format_crater_csv(const CraterCounts& counts);
// Writes format_crater_csv(counts) to `path` atomically.
void write_crater_csv(const CraterCounts& counts, const std::string& path);

}  // namespace craterkit::chronology
