// Shipped bodies: every value present and positive, the stated gravity consistent with G M / R^2 from
// the stated density and radius (an independent hand computation), and strict file checking.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "craterkit/chronology/body.hpp"
#include "craterkit/common/input_error.hpp"

namespace ck = craterkit::chronology;

TEST(Bodies, ShippedBodiesAreSelfConsistent) {
  for (const std::string name : {"ryugu", "bennu"}) {
    const auto b = ck::load_body(name);
    const double G = 6.674e-11;
    const double g_sphere = G * (4.0 / 3.0) * M_PI * b.mean_radius * b.bulk_density;
    // The stated gravity uses the measured mass; a uniform sphere of the stated density and radius
    // agrees within the rounding of the density (about 2 %).
    EXPECT_NEAR(b.surface_gravity / g_sphere, 1.0, 0.03) << name;
    // The surface of these top-shaped bodies exceeds that of the sphere of mean radius by under 10 %.
    const double sphere_area = 4.0 * M_PI * b.mean_radius * b.mean_radius;
    EXPECT_GT(b.surface_area / sphere_area, 0.99) << name;
    EXPECT_LT(b.surface_area / sphere_area, 1.10) << name;
    ASSERT_TRUE(b.main_belt.has_value()) << name;
    EXPECT_DOUBLE_EQ(b.main_belt->intrinsic_probability_km2_yr, 2.86e-18);
    EXPECT_FALSE(b.citations.empty());
    EXPECT_THROW(ck::environment(b, ck::CollisionRegion::near_earth), craterkit::InputError);
  }
}

TEST(Bodies, UnknownKeyAndBadValueAreNamed) {
  const auto path = std::filesystem::temp_directory_path() / "ck_body_bad.toml";
  std::ofstream(path)
      << "name = \"x\"\nmean_radius_m = 100\nbulk_density_kg_m3 = -3\nsurface_gravity_m_s2 = 1e-4\n"
         "surface_area_m2 = 1e5\n";
  try {
    ck::load_body_file(path);
    FAIL();
  } catch (const craterkit::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("bulk_density_kg_m3"), std::string::npos) << e.what();
  }
  std::ofstream(path) << "name = \"x\"\nradius = 100\n";
  try {
    ck::load_body_file(path);
    FAIL();
  } catch (const craterkit::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("unknown key radius"), std::string::npos) << e.what();
  }
  EXPECT_THROW(ck::load_body("vesta_not_shipped"), craterkit::InputError);
}
