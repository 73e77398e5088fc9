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
//  .binned, .stat  craterstats binned counts (below).
// A crater's fraction (0 < f <= 1; craterstats' partial craters) weights it in the fits; a .diam crater table
// with a reference_area column (km^2, buffered counting) gives each crater the weight 1 km^2 / reference_area
// on a nominal area of 1 km^2, as craterstats reads it.
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
  // Buffered counting (a craterstats .diam with a reference_area column): each crater was counted on its
  // own area A_i; area is then a nominal 1 km^2 and a crater's fraction is 1 km^2 / A_i (it may exceed 1).
  bool buffered = false;
  bool binned() const { return !bins.empty(); }
};

void validate(const CraterCounts& counts);

CraterCounts read_crater_counts(const std::string& path);  // by extension: .csv .diam .scc .binned .stat
CraterCounts read_crater_csv(const std::string& path);
CraterCounts read_craterstats_diam(const std::string& path);
CraterCounts read_crater_tools_scc(const std::string& path);
// craterstats binned counts: "area = X" (km^2) and "table = {diameter,frequency" rows (bin lower edge in km,
// craters in the bin) up to "}"; bins in any order. They become cumulative counts N(>=D_j), the last bin
// open-ended (end the table with an empty bin, e.g. "0.7 0", to close the last one, as craterstats asks).
CraterCounts read_craterstats_binned(const std::string& path);
// craterstats / CraterTools .stat tables: rows of 7 or 11 numbers, of which D (km, column 1) and the
// cumulative count C(D) (column 5) are used; the area from a "#Area : X qkm" comment, else C/N_cum of the
// first row with craters (column 6, per km^2).
CraterCounts read_craterstats_stat(const std::string& path);

// The counts as a craterkit .csv (the format read_crater_csv reads back exactly): '#' comment lines with
// the source and "area_m2 = X", then diameter_m,fraction (unbinned) or diameter_m,cumulative_count
// (binned), every number with 17 significant digits. Validates the counts first (InputError).
std::string format_crater_csv(const CraterCounts& counts);
// Writes format_crater_csv(counts) to `path` atomically.
void write_crater_csv(const CraterCounts& counts, const std::string& path);
// The counts in a craterstats format, for extension ".diam" (area, crater = {diameter, fraction}; buffered
// counts as crater = {diameter, reference_area}), ".scc" (Total_area, crater = {diam, fraction}; no unit
// boundary or coordinates) or ".binned" (binned counts: area, table = {diameter,frequency}); km and km^2,
// 17 significant digits. InputError for a format that cannot hold the counts.
std::string format_craterstats(const CraterCounts& counts, const std::string& extension);
// Writes the counts atomically in the format of the path's extension: .csv, .diam, .scc or .binned.
void write_crater_counts(const CraterCounts& counts, const std::string& path);

}  // namespace craterkit::chronology
