// Crater-count readers: CSV, craterstats .diam and CraterTools .scc, with errors that name the line.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "craterkit/chronology/crater_counts.hpp"
#include "craterkit/common/data_path.hpp"
#include "craterkit/common/input_error.hpp"

namespace ck = craterkit::chronology;

namespace {

std::string temp_file(const std::string& name, const std::string& text) {
  const auto path = std::filesystem::temp_directory_path() / ("ck_counts_" + name);
  std::ofstream(path) << text;
  return path.string();
}

// Expects InputError whose message contains every fragment.
void expect_error(const std::string& path, std::initializer_list<std::string> fragments) {
  try {
    ck::read_crater_counts(path);
    FAIL() << "expected InputError for " << path;
  } catch (const craterkit::InputError& e) {
    for (const auto& f : fragments) EXPECT_NE(std::string(e.what()).find(f), std::string::npos) << e.what();
  }
}

}  // namespace

TEST(CraterCounts, CsvUnbinnedWithArea) {
  const auto path =
      temp_file("a.csv", "# unit A\n# area_km2 = 0.25\ndiameter_m,fraction,lon\n20.5,1,3\n31,0.5,4\n");
  const auto c = ck::read_crater_counts(path);
  EXPECT_DOUBLE_EQ(c.area, 0.25e6);
  ASSERT_EQ(c.diameters.size(), 2u);
  EXPECT_DOUBLE_EQ(c.diameters[1], 31.0);
  EXPECT_DOUBLE_EQ(c.fractions[1], 0.5);
  EXPECT_FALSE(c.binned());
}

TEST(CraterCounts, CsvBinnedCumulative) {
  const auto path = temp_file("b.csv", "# area_m2 = 2.7e6\ndiameter_km,cumulative_count\n0.02,77\n0.1,20\n");
  const auto c = ck::read_crater_counts(path);
  ASSERT_TRUE(c.binned());
  EXPECT_DOUBLE_EQ(c.bins[0].diameter, 20.0);
  EXPECT_DOUBLE_EQ(c.bins[1].cumulative_count, 20.0);
}

TEST(CraterCounts, CraterstatsDiam) {
  const auto path =
      temp_file("c.diam", "# sample\narea = 0.5\n#\ncrater = {diameter, fraction\n0.021, 1\n0.035, 0.8\n}\n");
  const auto c = ck::read_crater_counts(path);
  EXPECT_DOUBLE_EQ(c.area, 0.5e6);
  ASSERT_EQ(c.diameters.size(), 2u);
  EXPECT_DOUBLE_EQ(c.diameters[0], 21.0);
  EXPECT_DOUBLE_EQ(c.fractions[1], 0.8);
}

TEST(CraterCounts, CraterToolsScc) {
  const auto path =
      temp_file("d.scc",
                "# Spatial crater count\na-axis radius = 0.448 <km>\n"
                "unit_boundary = {vertex, sub_area, tag, lon, lat\n1\t1\text\t0\t0\n2\t1\text\t1\t1\n}\n"
                "Total_area = 0.3 <km^2>\n# crater_diameters:\n"
                "crater = {diam, fraction, lon, lat, topo_scale_factor\n"
                "0.04\t1\t10\t2\t1\n0.025\t0.5\t11\t3\t1\n}\n");
  const auto c = ck::read_crater_counts(path);
  EXPECT_DOUBLE_EQ(c.area, 0.3e6);
  ASSERT_EQ(c.diameters.size(), 2u);
  EXPECT_DOUBLE_EQ(c.diameters[0], 40.0);
  EXPECT_DOUBLE_EQ(c.fractions[1], 0.5);
}

TEST(CraterCounts, MalformedFilesNameTheLine) {
  expect_error(temp_file("e1.csv", "# area_km2 = 1\ndiameter_m\n20\n3x\n"), {"e1.csv:4", "'3x'"});
  expect_error(temp_file("e2.csv", "# area_km2 = 1\ndiameter_m\n20\n-5\n"), {"e2.csv:4", "-5"});
  expect_error(temp_file("e3.csv", "diameter_m\n20\n"), {"area"});
  expect_error(temp_file("e4.csv", "# area_km2 = 1\nsize\n20\n"), {"e4.csv:2", "diameter_m"});
  expect_error(temp_file("e5.diam", "area = 1\ncrater = {diameter\n0.1\n0.2 ,\nfoo\n}\n"),
               {"e5.diam:5", "'foo'"});
  expect_error(temp_file("e6.diam", "area = 1\ncrater = {diameter\n0.1\n"), {"e6.diam:2", "never closed"});
  expect_error(temp_file("e7.scc", "crater = {diam, fraction\n0.1\t1\n}\n"), {"Total_area"});
  expect_error(temp_file("e8.scc", "Total_area = 1 <km^2>\ncrater = {diam, fraction\n0.1\t1.5\n}\n"),
               {"e8.scc:3", "fraction"});
  expect_error(temp_file("e9.csv", "# area_km2 = 1\ndiameter_m,cumulative_count\n10,5\n20,9\n"),
               {"e9.csv:4", "non-increasing"});
  expect_error(temp_file("e10.txt", "x"), {"extension"});
}

TEST(CraterCounts, ShippedCountFilesParse) {
  const auto dir = craterkit::data_file("craters");
  int files = 0;
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    const auto ext = entry.path().extension();
    if (ext != ".csv" && ext != ".diam" && ext != ".scc") continue;
    const auto c = ck::read_crater_counts(entry.path().string());
    EXPECT_GT(c.area, 0.0) << entry.path();
    EXPECT_TRUE(c.binned() || !c.diameters.empty()) << entry.path();
    ++files;
  }
  EXPECT_GE(files, 3);
}

// Every shipped count file is either labelled synthetic in its header or a real (published) count listed here
// with the values its source prints, and the file must reproduce them. A new real count needs an entry: the
// numbers it is checked against are the ones quoted in its header (paper, table or paragraph, URL read).
namespace {

struct QuotedCount {
  double diameter_m;  // the size the source quotes N(>=D) at
  double cumulative;  // the number of craters the source prints
};

struct RealCount {
  const char* file;  // in data/craters/
  double area_km2;   // the counting area the header gives
  std::vector<QuotedCount> quoted;
};

const std::vector<RealCount>& real_counts() {
  static const std::vector<RealCount> counts = {
      // Hirata et al. (2020), Icarus 338, 113527, abstract: 77 craters larger than 20 m, whole surface.
      {"ryugu_global_hirata2020.csv", 2.7, {{20.0, 77.0}}},
      // The same, and 11 craters of at least 100 m (Space.com's report of that paper; see the header).
      {"ryugu_global_hirata2020_20_100m.csv", 2.7, {{20.0, 77.0}, {100.0, 11.0}}},
  };
  return counts;
}

bool labelled_synthetic(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::string line;
  for (int i = 0; i < 5 && std::getline(in, line); ++i) {
    if (line.find("SYNTHETIC") != std::string::npos) return true;
  }
  return false;
}

// N(>=D) of a count: the cumulative count of the bin at exactly D (binned), or the craters >= D with their
// fractions (unbinned). NaN for a binned count without a bin at D.
double cumulative_at(const ck::CraterCounts& c, double diameter) {
  if (c.binned()) {
    for (const auto& b : c.bins) {
      if (b.diameter == diameter) return b.cumulative_count;
    }
    return std::nan("");
  }
  double n = 0.0;
  for (std::size_t i = 0; i < c.diameters.size(); ++i) {
    if (c.diameters[i] >= diameter) n += c.fractions[i];
  }
  return n;
}

}  // namespace

TEST(CraterCounts, ShippedRealCountsReproduceTheNumbersTheirSourcesPrint) {
  int real = 0;
  for (const auto& entry : std::filesystem::directory_iterator(craterkit::data_file("craters"))) {
    const auto ext = entry.path().extension();
    if (ext != ".csv" && ext != ".diam" && ext != ".scc" && ext != ".binned" && ext != ".stat") continue;
    if (labelled_synthetic(entry.path())) continue;
    const auto name = entry.path().filename().string();
    const RealCount* expected = nullptr;
    for (const auto& r : real_counts()) {
      if (name == r.file) expected = &r;
    }
    ASSERT_NE(expected, nullptr) << name
                                 << " is neither labelled SYNTHETIC nor listed in real_counts() with the "
                                 << "values its source prints";
    const auto c = ck::read_crater_counts(entry.path().string());
    EXPECT_DOUBLE_EQ(c.area, expected->area_km2 * 1e6) << name;
    for (const auto& q : expected->quoted) {
      EXPECT_DOUBLE_EQ(cumulative_at(c, q.diameter_m), q.cumulative)
          << name << " N(>=" << q.diameter_m << " m)";
    }
    ++real;
  }
  EXPECT_EQ(real, static_cast<int>(real_counts().size()))
      << "a listed real count is missing from data/craters";
}

TEST(CraterCounts, ShippedSyntheticUnitIsTheSameInAllFormats) {
  const auto csv = ck::read_crater_counts(craterkit::data_file("craters/ryugu_synthetic_unit.csv").string());
  for (const char* other : {"craters/ryugu_synthetic_unit.diam", "craters/ryugu_synthetic_unit.scc"}) {
    const auto c = ck::read_crater_counts(craterkit::data_file(other).string());
    EXPECT_DOUBLE_EQ(c.area, csv.area) << other;
    ASSERT_EQ(c.diameters.size(), csv.diameters.size()) << other;
    for (std::size_t i = 0; i < c.diameters.size(); ++i) {
      EXPECT_NEAR(c.diameters[i], csv.diameters[i], 0.006) << other << " row " << i;  // km files keep 0.01 m
    }
  }
}

TEST(CraterCounts, WrittenCsvReadsBackExactly) {
  ck::CraterCounts unbinned;
  unbinned.source = "test";
  unbinned.area = 812345.678;
  unbinned.diameters = {12.345678901234567, 40.0, 1.0 / 3.0};
  unbinned.fractions = {1.0, 0.5, 0.25};
  const auto path = std::filesystem::temp_directory_path() / "ck_counts_written.csv";
  ck::write_crater_csv(unbinned, path.string());
  const auto back = ck::read_crater_counts(path.string());
  EXPECT_EQ(back.area, unbinned.area);
  EXPECT_EQ(back.diameters, unbinned.diameters);
  EXPECT_EQ(back.fractions, unbinned.fractions);

  ck::CraterCounts binned;
  binned.area = 2.7e6;
  binned.bins = {{10.0, 120.0}, {20.0, 77.0}, {40.0, 9.5}};
  ck::write_crater_csv(binned, path.string());
  const auto bins = ck::read_crater_counts(path.string());
  ASSERT_EQ(bins.bins.size(), 3u);
  EXPECT_EQ(bins.bins[2].diameter, 40.0);
  EXPECT_EQ(bins.bins[2].cumulative_count, 9.5);
  EXPECT_EQ(bins.area, 2.7e6);

  ck::CraterCounts bad = unbinned;
  bad.area = 0.0;
  EXPECT_THROW(ck::write_crater_csv(bad, path.string()), craterkit::InputError);
  std::filesystem::remove(path);
}

TEST(CraterCounts, CraterstatsBinnedFile) {
  // Bins listed out of order; the empty last bin closes the bin below it.
  const auto path = temp_file("b1.binned",
                              "# binned\n# area in km^2\narea = 123.0\n\ntable = {diameter,frequency\n"
                              "0.1  3\n0.06   1\n0.2 8\n0.7 0\n}\n");
  const auto c = ck::read_crater_counts(path);
  EXPECT_DOUBLE_EQ(c.area, 123e6);
  ASSERT_EQ(c.bins.size(), 4u);
  EXPECT_DOUBLE_EQ(c.bins[0].diameter, 60.0);
  EXPECT_DOUBLE_EQ(c.bins[0].cumulative_count, 12.0);
  EXPECT_DOUBLE_EQ(c.bins[1].cumulative_count, 11.0);
  EXPECT_DOUBLE_EQ(c.bins[2].diameter, 200.0);
  EXPECT_DOUBLE_EQ(c.bins[2].cumulative_count, 8.0);
  EXPECT_DOUBLE_EQ(c.bins[3].cumulative_count, 0.0);
  expect_error(temp_file("b2.binned", "area = 1\ntable = {diameter,frequency,event_frequency\n0.1 1 1\n}\n"),
               {"event_frequency", ":2"});
  expect_error(temp_file("b3.binned", "area = 1\ntable = {diameter,frequency\n0.1 -1\n}\n"),
               {"frequency", ":3"});
  expect_error(temp_file("b4.binned", "table = {diameter,frequency\n0.1 1\n}\n"), {"area"});
}

TEST(CraterCounts, CraterstatsStatFile) {
  const std::string rows =
      "#     D        F(D)    N_dif    Error       C(D)    N_cum    Error\n"
      "     .0600       10  2.93E+00  9.28E-01      40  2.00E-01  6.41E-02\n"
      "     .1000       20  1.29E+01  1.95E+00      30  1.50E-01  5.78E-02\n"
      "    1.2000       10  2.93E-02  2.93E-02      10  5.00E-02  2.93E-03\n";
  const auto with_area =
      ck::read_crater_counts(temp_file("s1.stat", "#Area :  250.5  qkm , Mes.No. : X\n" + rows));
  EXPECT_DOUBLE_EQ(with_area.area, 250.5e6);
  ASSERT_EQ(with_area.bins.size(), 3u);
  EXPECT_DOUBLE_EQ(with_area.bins[1].diameter, 100.0);
  EXPECT_DOUBLE_EQ(with_area.bins[1].cumulative_count, 30.0);
  // Without the header the area is C / N_cum of the first row (40 / 0.2 km^-2 = 200 km^2).
  const auto derived = ck::read_crater_counts(temp_file("s2.stat", rows));
  EXPECT_DOUBLE_EQ(derived.area, 200e6);
  expect_error(temp_file("s3.stat", "  .06 10 1 1 40\n"), {"7 or 11 columns", ":1"});
}

TEST(CraterCounts, BufferedDiamWithReferenceAreas) {
  // Each crater counted on its own area: weight 1 km^2 / reference_area on a nominal 1 km^2.
  const auto path = temp_file(
      "r1.diam", "area = 50\ncrater = {diameter, reference_area\n1.0  200\n2.5  400\n0.4  0.5\n}\n");
  const auto c = ck::read_crater_counts(path);
  EXPECT_TRUE(c.buffered);
  EXPECT_DOUBLE_EQ(c.area, 1e6);
  ASSERT_EQ(c.fractions.size(), 3u);
  EXPECT_DOUBLE_EQ(c.diameters[1], 2500.0);
  EXPECT_DOUBLE_EQ(c.fractions[1], 1.0 / 400.0);
  EXPECT_DOUBLE_EQ(c.fractions[2], 2.0);  // an area below the nominal one
  // Written as .csv and read back, it stays buffered.
  const auto csv = std::filesystem::temp_directory_path() / "ck_counts_buffered.csv";
  ck::write_crater_csv(c, csv.string());
  const auto back = ck::read_crater_counts(csv.string());
  EXPECT_TRUE(back.buffered);
  EXPECT_EQ(back.fractions, c.fractions);
  std::filesystem::remove(csv);
  expect_error(temp_file("r2.diam", "crater = {diameter, reference_area\n1.0  0\n}\n"),
               {"reference_area", ":2"});
  expect_error(temp_file("r3.diam", "crater = {diameter, fraction, reference_area\n1.0 1 2\n}\n"),
               {"give one"});
  // A fraction above 1 without buffering stays an error.
  expect_error(temp_file("r4.diam", "area = 1\ncrater = {diameter, fraction\n1.0  1.5\n}\n"),
               {"fraction", ":3"});
}

TEST(CraterCounts, WrittenInCraterstatsFormatsReadsBack) {
  ck::CraterCounts unbinned;
  unbinned.area = 812345.678;
  unbinned.diameters = {12.345678901234567, 40.0, 1.0 / 3.0};
  unbinned.fractions = {1.0, 0.5, 0.25};
  ck::CraterCounts binned;
  binned.area = 2.7e6;
  binned.bins = {{10.0, 120.0}, {20.0, 77.0}, {40.0, 9.0}};
  ck::CraterCounts buffered = unbinned;
  buffered.area = 1e6;
  buffered.buffered = true;
  buffered.fractions = {0.01, 2.0, 1.0 / 3.0};
  const auto dir = std::filesystem::temp_directory_path();
  const auto same = [](double a, double b) { return std::abs(a - b) <= 1e-15 * std::abs(b); };
  for (const auto* counts : {&unbinned, &buffered}) {
    for (const char* ext : {".diam", ".scc"}) {
      const auto path = (dir / (std::string("ck_counts_out") + ext)).string();
      if (counts->buffered && std::string(ext) == ".scc") {
        EXPECT_THROW(ck::write_crater_counts(*counts, path), craterkit::InputError);
        continue;
      }
      ck::write_crater_counts(*counts, path);
      const auto back = ck::read_crater_counts(path);
      EXPECT_EQ(back.buffered, counts->buffered) << ext;
      EXPECT_TRUE(same(back.area, counts->area)) << ext;
      ASSERT_EQ(back.diameters.size(), 3u) << ext;
      for (std::size_t i = 0; i < 3; ++i) {
        EXPECT_TRUE(same(back.diameters[i], counts->diameters[i])) << ext << " " << i;
        EXPECT_TRUE(same(back.fractions[i], counts->fractions[i])) << ext << " " << i;
      }
      std::filesystem::remove(path);
    }
  }
  const auto path = (dir / "ck_counts_out.binned").string();
  ck::write_crater_counts(binned, path);
  const auto back = ck::read_crater_counts(path);
  ASSERT_EQ(back.bins.size(), 3u);
  for (std::size_t k = 0; k < 3; ++k) {
    EXPECT_TRUE(same(back.bins[k].diameter, binned.bins[k].diameter)) << k;
    EXPECT_EQ(back.bins[k].cumulative_count, binned.bins[k].cumulative_count) << k;
  }
  EXPECT_THROW(ck::write_crater_counts(unbinned, path), craterkit::InputError);
  EXPECT_THROW(ck::write_crater_counts(binned, (dir / "x.diam").string()), craterkit::InputError);
  EXPECT_THROW(ck::write_crater_counts(binned, (dir / "x.txt").string()), craterkit::InputError);
  std::filesystem::remove(path);
}
