// Chronology systems whose production function is Hartmann's table of incremental densities in root-2
// diameter bins (chronology_system.hpp, ProductionForm::tabular_incremental_root2): N(>=D, t) and model ages
// against craterstats 3.6.10 run on the same numbers, and malformed files rejected naming the key.
//
// The reference values were computed with craterstats' own code from the snapshot of its repository
// (github.com/ggmichael/craterstats at version 3.6.10), Productionfn and Chronologyfn (and Cratercount and
// Craterpdf for the ages) run by /usr/bin/python3 with numpy 1.24 and scipy 1.10. Its package __init__
// imports the plotting modules and modules written for Python >= 3.12, so the four modules were imported on
// their own (the package registered from src/craterstats/__init__.py without executing it, constants.py
// loaded, the plotting-only imports colorama, palettable, progressbar, astropy, pyproj, shapely, shapefile,
// spherely stubbed). With F = src/craterstats/config/functions.txt:
//   pf = Productionfn(F, '<production name>'); cf = Chronologyfn(F, '<chronology name>')
//   N(>=D, t) = pf.C(numpy.array([D_km]), cf.a0(t_Gyr))[0]                                 (printed %.17g)
//   cc = Cratercount('tests/chronology/data/synthetic_lunar_unit.diam')
//   pdf = Craterpdf(pf, cf, cc, numpy.clip([d_min_km, d_max_km], *pf.range), n_samples=n); pdf.median1sigma()
// with craterstats' default n = 5000 and with n = 500000.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "craterkit/chronology/chronology_system.hpp"
#include "craterkit/chronology/crater_counts.hpp"
#include "craterkit/chronology/model_age.hpp"
#include "craterkit/common/input_error.hpp"

namespace ck = craterkit::chronology;

namespace {

const std::string kSyntheticUnit = std::string(CRATERKIT_TEST_DATA) + "/synthetic_lunar_unit.diam";

// The error message of loading `text` as a system file, or "" if it loads.
std::string load_error(const std::string& text) {
  const auto path = std::filesystem::temp_directory_path() / "craterkit_test_tabular_system.toml";
  {
    std::ofstream out(path);
    out << text;
  }
  try {
    ck::load_chronology_system_file(path);
  } catch (const craterkit::InputError& e) {
    std::filesystem::remove(path);
    return e.what();
  }
  std::filesystem::remove(path);
  return "";
}

std::string system_file(const std::string& production) {
  return "name = \"test_tabular\"\nbody = \"Mars\"\ncitation = \"test\"\n[production]\n" + production +
         "\n[chronology]\ncoefficients = [3.79e-14, 6.93, 0.0, 5.84e-4]\n";
}

}  // namespace

TEST(HartmannSystems, ShippedAndLoaded) {
  const auto names = ck::chronology_system_names();
  for (const char* name : {"moon_hartmann2010", "mars_hartmann2005", "mars_hartmann_daubar2016"}) {
    EXPECT_NE(std::find(names.begin(), names.end(), name), names.end()) << name;
  }
  const auto mars = ck::load_chronology_system("mars_hartmann2005");
  EXPECT_EQ(mars.production_form, ck::ProductionForm::tabular_incremental_root2);
  EXPECT_EQ(ck::to_string(mars.production_form), "tabular_incremental_root2");
  EXPECT_EQ(mars.title, "Mars, Hartmann 2004 iteration");
  EXPECT_EQ(mars.body, "Mars");
  EXPECT_TRUE(mars.production.empty());
  EXPECT_EQ(mars.incremental_density.size(), 36u);
  EXPECT_EQ(mars.index_1km, 16u);
  // craterstats' range: the centres of the first and last bins, 2^(-8 + 1/4) and 2^(19/2 + 1/4) km.
  EXPECT_NEAR(mars.min_diameter / 4.645340292979379, 1.0, 1e-14);
  EXPECT_NEAR(mars.max_diameter / 861077.9292198038, 1.0, 1e-14);
  const auto moon = ck::load_chronology_system("moon_hartmann2010");
  EXPECT_EQ(moon.body, "Moon");
  EXPECT_NEAR(moon.min_diameter / 13.13900648833929, 1.0, 1e-14);
  EXPECT_NEAR(moon.max_diameter / 107634.74115247547, 1.0, 1e-14);
  const auto hd = ck::load_chronology_system("mars_hartmann_daubar2016");
  EXPECT_EQ(hd.index_1km, 20u);
  EXPECT_NEAR(hd.min_diameter / 1.1613350732448448, 1.0, 1e-14);
  // From 2^-5 km up Hartmann & Daubar's table is Hartmann's (2005).
  for (std::size_t i = 6; i < mars.incremental_density.size(); ++i) {
    EXPECT_EQ(hd.incremental_density[i + 4], mars.incremental_density[i]) << i;
  }
}

TEST(HartmannSystems, CumulativeDensityMatchesCraterstats) {
  // pf.C(D, cf.a0(t)) of craterstats 3.6.10 (see the top of the file) at t = 0.001, 0.5, 1, 3, 3.9 Gyr:
  // inside bins, on a bin edge (62.5 m = 2^-4 km, 64 km = 2^6 km), near both ends of the range and above
  // the last bin's lower edge, where the held end value makes N(>=D) flat (Moon 100 and 107 km, Mars 800 km).
  struct Case {
    const char* system;
    double diameter_m;
    double n[5];
  };
  const double ages_gyr[5] = {0.001, 0.5, 1.0, 3.0, 3.9};
  const Case cases[] = {
      {"moon_hartmann2010",
       14,
       {3.5708675531928087, 1785.4337829532244, 3570.8677877158352, 10959.71738661434, 140281.64203901478}},
      {"moon_hartmann2010",
       50,
       {0.027779406371528124, 13.889703235216666, 27.779408195989653, 85.260637216197182,
        1091.3148366935866}},
      {"moon_hartmann2010",
       300,
       {2.9804172030788199e-05, 0.014902086068451184, 0.029804173988229814, 0.091475054040414353,
        1.1708578181103146}},
      {"moon_hartmann2010",
       1000,
       {3.9700000017871953e-07, 0.00019850000079609496, 0.00039700002625239506, 0.0012184735892974391,
        0.015596157260093394}},
      {"moon_hartmann2010",
       5000,
       {1.8239461880208912e-08, 9.1197309725741522e-06, 1.8239463078117772e-05, 5.598061101770055e-05,
        0.00071653782290971623}},
      {"moon_hartmann2010",
       20000,
       {1.4137473248017159e-09, 7.0687366491759739e-07, 1.4137474176520674e-06, 4.3390775225071196e-06,
        5.5539107288962245e-05}},
      {"moon_hartmann2010",
       64000,
       {9.2774923078394542e-11, 4.6387461704354107e-08, 9.2774929171551028e-08, 2.8474507171092086e-07,
        3.6446657165549956e-06}},
      {"moon_hartmann2010",
       100000,
       {2.6257053701432364e-11, 1.312852689745871e-08, 2.6257055425910724e-08, 8.0588227842713287e-08,
        1.0315091650627345e-06}},
      {"moon_hartmann2010",
       107000,
       {2.6257053701432364e-11, 1.312852689745871e-08, 2.6257055425910724e-08, 8.0588227842713287e-08,
        1.0315091650627345e-06}},
      {"mars_hartmann2005",
       5,
       {5.1262993975361137, 2563.149707916642, 5126.2997350560772, 15734.539828915949, 201840.04981800987}},
      {"mars_hartmann2005",
       62.5,
       {0.0051729707025951642, 2.5864853605294593, 5.1729710431880083, 15.87779160790336, 203.6776597209188}},
      {"mars_hartmann2005",
       100,
       {0.0012847381134241239, 0.64236905900485364, 1.2847381980123871, 3.9433442036401876,
        50.584561046367178}},
      {"mars_hartmann2005",
       350,
       {2.0273872161127889e-05, 0.010136936116745448, 0.020273873495977084, 0.062228134618695932,
        0.79825212100815102}},
      {"mars_hartmann2005",
       1000,
       {5.8400000026355921e-07, 0.00029200000117400794, 0.000584000038714622, 0.0017925155266292981,
        0.022994089889398436}},
      {"mars_hartmann2005",
       3700,
       {4.8938675552213519e-08, 2.4469337863444554e-05, 4.8938678774378038e-05, 0.00015021119133634729,
        0.0019268840825476979}},
      {"mars_hartmann2005",
       16000,
       {3.4087296662686735e-09, 1.704364839217687e-06, 3.4087298907023761e-06, 1.0462672688546211e-05,
        0.00013421341835525346}},
      {"mars_hartmann2005",
       100000,
       {7.7901330476923728e-11, 3.8950665377487338e-08, 7.7901335606014065e-08, 2.3910846637319564e-07,
        3.0672434840440256e-06}},
      {"mars_hartmann2005",
       800000,
       {5.3725102066229753e-13, 2.686255112899471e-10, 5.3725105603536721e-10, 1.6490253352739544e-09,
        2.1153421672439644e-08}},
      {"mars_hartmann_daubar2016",
       1.2,
       {199.66158308659925, 99830.791899623175, 199661.59623248974, 612836.45135718444, 7861363.6761659654}},
      {"mars_hartmann_daubar2016",
       2,
       {82.498349089356125, 41249.174691907734, 82498.354521118483, 253218.44451578209, 3248243.927793704}},
      {"mars_hartmann_daubar2016",
       4,
       {16.564765574208568, 8282.3828166663898, 16564.766664846982, 50843.492248875133, 652211.82951758208}},
      {"mars_hartmann_daubar2016",
       10,
       {1.2032912271885821, 601.64561574172956, 1203.291306414312, 3693.3530938680447, 47377.716829815043}},
      {"mars_hartmann_daubar2016",
       30,
       {0.043489281208861218, 21.744640682043212, 43.489284072232927, 133.48495166720946,
        1712.3226727578476}},
      {"mars_hartmann_daubar2016",
       50,
       {0.010097238562534876, 5.0486192992873473, 10.097239227345755, 30.992220704204751,
        397.56303259733858}},
      {"mars_hartmann_daubar2016",
       1000,
       {5.8400000026355921e-07, 0.00029200000117400794, 0.000584000038714622, 0.0017925155266292981,
        0.022994089889398436}},
  };
  for (const auto& c : cases) {
    const auto system = ck::load_chronology_system(c.system);
    const auto r = ck::chronology_production(system);
    const auto clock = ck::chronology_clock(system);
    for (int k = 0; k < 5; ++k) {
      const double t = ages_gyr[k] * 1e9;
      const double n = ck::cumulative_density(system, c.diameter_m, t);
      EXPECT_NEAR(n / c.n[k], 1.0, 1e-12) << c.system << " D = " << c.diameter_m << " m, t = " << ages_gyr[k];
      // The present-day rate times the clock gives the same density (per m^2 -> per km^2).
      EXPECT_NEAR(r(c.diameter_m) * clock(t) * 1e6 / n, 1.0, 1e-12) << c.system << " " << c.diameter_m;
    }
  }
}

TEST(HartmannSystems, TableByHand) {
  // At a bin edge N(>=D_i) is the sum of the bins from i up, relative to the sum from 1 km up.
  const auto mars = ck::load_chronology_system("mars_hartmann2005");
  const auto& h = mars.incremental_density;
  double from_1km = 0.0, from_4km = 0.0;
  for (std::size_t i = 16; i < h.size(); ++i) from_1km += h[i];
  for (std::size_t i = 20; i < h.size(); ++i) from_4km += h[i];
  const double n1 = ck::n1(mars, 2e9);
  EXPECT_NEAR(ck::cumulative_density(mars, 4000.0, 2e9) / (n1 * from_4km / from_1km), 1.0, 1e-13);
  EXPECT_NEAR(ck::cumulative_density(mars, 1000.0, 2e9) / n1, 1.0, 1e-13);
  // Between two edges the interpolation is a power law: halfway in log D is the geometric mean.
  double from_2km = 0.0, from_2828m = 0.0;
  for (std::size_t i = 18; i < h.size(); ++i) from_2km += h[i];
  for (std::size_t i = 19; i < h.size(); ++i) from_2828m += h[i];
  EXPECT_NEAR(ck::cumulative_density(mars, 2000.0 * std::pow(2.0, 0.25), 2e9) /
                  (n1 * std::sqrt(from_2km * from_2828m) / from_1km),
              1.0, 1e-12);
  // The table's N(>=1 km) is the 1-Gyr isochron of N(1)(t) = ... + 5.84e-4 t (Michael 2013).
  EXPECT_NEAR(from_1km / ck::n1(mars, 1e9), 1.0, 1e-3);
  // Outside craterstats' range (the centres of the first and last bins) the function is refused.
  const auto r = ck::chronology_production(mars);
  EXPECT_THROW(r(4.6), craterkit::InputError);
  EXPECT_NO_THROW(r(4.65));
  EXPECT_THROW(r(862e3), craterkit::InputError);
  EXPECT_THROW(ck::cumulative_density(mars, 1.0, 1e9), craterkit::InputError);
}

TEST(HartmannSystems, AgesMatchCraterstats) {
  // craterstats 3.6.10's Poisson age (Craterpdf.median1sigma, see the top of the file) of the synthetic
  // count: median and 1-sigma bounds in Gyr. As for the polynomial systems (test_chronology_systems.cpp),
  // craterstats counts each crater once and puts a prior uniform in crater density. Its default likelihood
  // grid (n_samples = 5000, steps of 0.003 in log10 N(1)) reads ages about 0.35 % low where N(1) grows
  // linearly, so 0.6 % is allowed; with n_samples = 500000 its grid error is about 5e-5 and 2e-4 is allowed.
  struct Case {
    const char* system;
    double d_min_km, d_max_km, k;
    double median, low, high;                 // n_samples = 5000
    double fine_median, fine_low, fine_high;  // n_samples = 500000
  };
  const Case cases[] = {
      {"mars_hartmann2005", 0.2, 1.0, 60, 1.7215997, 1.5099902, 1.9521167, 1.7274862, 1.5151906, 1.9587209},
      {"mars_hartmann2005", 0.15, 3.0, 160, 1.768411, 1.6324972, 1.9116716, 1.7744611, 1.6381572, 1.9181106},
      {"mars_hartmann_daubar2016", 0.2, 1.0, 60, 1.7215997, 1.5099902, 1.9521167, 1.7274862, 1.5151906,
       1.9587209},
      {"moon_hartmann2010", 0.2, 1.0, 60, 1.7326566, 1.5196971, 1.9646494, 1.7385815, 1.5249228, 1.971298},
  };
  const auto counts = ck::read_crater_counts(kSyntheticUnit);
  for (const auto& c : cases) {
    const auto system = ck::load_chronology_system(c.system);
    ck::AgeFitOptions options;
    options.min_diameter = c.d_min_km * 1e3;
    options.max_diameter = c.d_max_km * 1e3;
    options.weight_by_fraction = false;
    options.prior_uniform_in_density = true;
    options.clock = ck::chronology_clock(system);
    const auto age = ck::fit_model_age(counts, ck::chronology_production(system), options);
    EXPECT_EQ(age.craters_in_range, c.k) << c.system;
    EXPECT_NEAR(age.median / 1e9 / c.median, 1.0, 6e-3) << c.system << " " << c.d_min_km;
    EXPECT_NEAR(age.sigma1_low / 1e9 / c.low, 1.0, 6e-3) << c.system << " " << c.d_min_km;
    EXPECT_NEAR(age.sigma1_high / 1e9 / c.high, 1.0, 6e-3) << c.system << " " << c.d_min_km;
    EXPECT_NEAR(age.median / 1e9 / c.fine_median, 1.0, 2e-4) << c.system << " " << c.d_min_km;
    EXPECT_NEAR(age.sigma1_low / 1e9 / c.fine_low, 1.0, 2e-4) << c.system << " " << c.d_min_km;
    EXPECT_NEAR(age.sigma1_high / 1e9 / c.fine_high, 1.0, 2e-4) << c.system << " " << c.d_min_km;
  }
}

TEST(HartmannSystems, BadFilesNameTheKey) {
  const std::string ok = "form = \"tabular_incremental_root2\"\nincremental_density = [4.0, 2.0, 1.0]\n";
  EXPECT_EQ(load_error(system_file(ok + "index_1km = 1")), "");
  const auto expect_error = [](const std::string& message, const std::vector<std::string>& parts) {
    EXPECT_FALSE(message.empty());
    for (const auto& part : parts)
      EXPECT_NE(message.find(part), std::string::npos) << message << " | " << part;
  };
  // index outside the table
  expect_error(load_error(system_file(ok + "index_1km = 3")), {"production.index_1km", "3", "[0, 2]"});
  expect_error(load_error(system_file(ok + "index_1km = -1")), {"production.index_1km", "-1"});
  expect_error(load_error(system_file(ok + "index_1km = 1.5")), {"production.index_1km", "integer"});
  expect_error(load_error(system_file(ok)), {"production.index_1km", "missing"});
  // non-positive densities
  expect_error(load_error(system_file("form = \"tabular_incremental_root2\"\n"
                                      "incremental_density = [4.0, -2.0, 1.0]\nindex_1km = 1")),
               {"production.incremental_density", "-2", "> 0", "element 1"});
  expect_error(load_error(system_file("form = \"tabular_incremental_root2\"\n"
                                      "incremental_density = [4.0, 0, 1.0]\nindex_1km = 1")),
               {"production.incremental_density", "0", "> 0"});
  expect_error(load_error(system_file("form = \"tabular_incremental_root2\"\n"
                                      "incremental_density = [4.0]\nindex_1km = 0")),
               {"production.incremental_density", "1 values", "at least 2"});
  expect_error(load_error(system_file("form = \"tabular_incremental_root2\"\nindex_1km = 0")),
               {"production.incremental_density", "missing"});
  // an unknown form, and the keys of the other form
  expect_error(load_error(system_file("form = \"tabular\"\nincremental_density = [4.0, 2.0]\nindex_1km = 0")),
               {"production.form", "tabular", "polynomial", "tabular_incremental_root2"});
  expect_error(load_error(system_file(ok + "index_1km = 1\ncoefficients = [1.0, 2.0]")),
               {"production.coefficients"});
  expect_error(load_error(system_file("incremental_density = [4.0, 2.0]\nindex_1km = 0\n"
                                      "coefficients = [1.0, -2.0]\nmin_diameter_km = 0.01\n"
                                      "max_diameter_km = 10.0")),
               {"incremental_density"});
  // A system built by hand must carry the table's range.
  auto system = ck::load_chronology_system("mars_hartmann2005");
  system.max_diameter *= 2.0;
  try {
    ck::validate(system);
    ADD_FAILURE() << "a range other than the table's was accepted";
  } catch (const craterkit::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("tabular_root2_range"), std::string::npos) << e.what();
  }
}
