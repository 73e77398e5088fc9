"""The Python package against the C++ results: every number is compared with what the craterkit program
(the same C++ libraries, through the command line and --json) prints for the same input, or with a closed
form. Run by CTest with /usr/bin/python3, PYTHONPATH at the built package, CRATERKIT_BIN the program and
CRATERKIT_DATA_DIR the source tree's data."""

import json
import math
import os
import subprocess
import tempfile
import unittest

import numpy as np

import craterkit as ck

CK = os.environ["CRATERKIT_BIN"]
DATA = os.environ["CRATERKIT_DATA_DIR"]
COUNTS = os.path.join(DATA, "craters", "ryugu_synthetic_unit.scc")
TABLE = os.path.join(DATA, "examples", "radii_example.csv")


def cli(*args):
    out = subprocess.run([CK, *map(str, args), "--json"], check=True, capture_output=True, text=True)
    return json.loads(out.stdout)


def close(a, b, rel=1e-12):
    return math.isclose(a, b, rel_tol=rel, abs_tol=0.0)


class Scaling(unittest.TestCase):
    def test_constant_sets(self):
        names = ck.constant_set_names()
        self.assertIn("jutzi2022_ryugu", names)
        self.assertGreaterEqual(len(names), 10)
        s = ck.load_constant_set("jutzi2022_ryugu")
        self.assertEqual(s.law.form, "hh2011")
        self.assertEqual((s.law.coefficient_1, s.law.coefficient_2, s.law.mu, s.law.nu), (0.6, 0.25, 0.44, 0.4))
        self.assertEqual(s.law.coefficient_names, ("H1", "H2"))
        self.assertEqual(s.strength, 0.05)
        self.assertIn("Jutzi", s.citation)
        self.assertEqual(repr(ck.law("jutzi2022_ryugu")), "ScalingLaw(form='hh2011', H1=0.6, H2=0.25, mu=0.44, nu=0.4)")

    def test_forward_matches_the_program_and_broadcasts(self):
        law = ck.law("jutzi2022_ryugu")
        radii = np.array([0.02, 0.056, 0.3])
        got = ck.crater_radius(law, radii, 2700.0, 2000.0, 1300.0, 1.4e-4, 0.05)
        self.assertEqual(got.shape, (3,))
        for a, r in zip(radii, got):
            want = cli("scale", "--params", "jutzi2022_ryugu", "--impactor-radius", repr(a), "--impactor-density",
                       2700, "--velocity", 2000, "--gravity", 1.4e-4, "--target-density", 1300, "--strength", 0.05)
            self.assertTrue(close(r, want["crater_radius"]), (r, want["crater_radius"]))
        # a number in, a number out; a 2-d grid of radius x strength broadcasts
        one = ck.crater_radius(law, 0.056, 2700, 2000, 1300, 1.4e-4, 0.05)
        self.assertIsInstance(one, float)
        self.assertTrue(close(one, got[1]))
        grid = ck.crater_radius(law, radii[:, None], 2700, 2000, 1300, 1.4e-4, np.array([0.0, 0.05, 1.0, 100.0]))
        self.assertEqual(grid.shape, (3, 4))
        self.assertTrue(np.all(np.diff(grid, axis=1) < 0))  # stronger targets, smaller craters

    def test_inverse_and_forms(self):
        law = ck.law("jutzi2022_ryugu")
        radii = np.geomspace(0.01, 1.0, 7)
        craters = ck.crater_radius(law, radii, 2700, 2000, 1300, 1.4e-4, 0.05)
        back = ck.impactor_radius(law, craters, 2700, 2000, 1300, 1.4e-4, 0.05)
        np.testing.assert_allclose(back, radii, rtol=1e-8)
        speeds = ck.impact_velocity(law, craters, radii, 2700, 1300, 1.4e-4, 0.05)
        np.testing.assert_allclose(speeds, 2000.0, rtol=1e-7)
        want = cli("scale", "--params", "jutzi2022_ryugu", "--crater-radius", repr(float(craters[3])),
                   "--impactor-density", 2700, "--velocity", 2000, "--gravity", 1.4e-4, "--target-density", 1300,
                   "--strength", 0.05)
        self.assertTrue(close(back[3], want["impactor_radius"], 1e-10))
        holsapple = law.convert("holsapple")
        self.assertEqual(holsapple.coefficient_names, ("K1", "K2"))
        self.assertTrue(close(holsapple.coefficient_2, (0.6 / 0.25) ** (2 / 0.44)))
        np.testing.assert_allclose(ck.crater_radius(holsapple, radii, 2700, 2000, 1300, 1.4e-4, 0.05), craters,
                                   rtol=1e-12)
        # the pure limits bracket the law
        g = ck.gravity_limit_radius(law, radii, 2700, 2000, 1300, 1.4e-4)
        s = ck.strength_limit_radius(law, radii, 2700, 2000, 1300, 0.05)
        self.assertTrue(np.all(craters <= np.minimum(g, s) * (1 + 1e-12)))

    def test_errors_are_value_errors_with_the_message(self):
        with self.assertRaisesRegex(ValueError, "cubic"):
            ck.ScalingLaw("cubic", 1, 1, 0.4, 0.4)
        with self.assertRaisesRegex(ValueError, "not known; available: .*jutzi2022_ryugu"):
            ck.load_constant_set("jutzi2023")
        with self.assertRaisesRegex(ValueError, "mu"):
            ck.ScalingLaw.hh2011(0.6, 0.25, -0.1, 0.4)
        with self.assertRaisesRegex(ValueError, "body 'vesta' is not known"):
            ck.load_body("vesta")
        # the same words as the program's error
        run = subprocess.run([CK, "scale", "--params", "jutzi2023", "--impactor-radius", "1"], capture_output=True,
                             text=True)
        self.assertEqual(run.returncode, 2)
        try:
            ck.load_constant_set("jutzi2023")
        except ValueError as e:
            self.assertIn(str(e), run.stderr)

    def test_fit_matches_the_program(self):
        want = cli("fit", TABLE, "--form", "hh2011", "--fix", "nu=0.4")
        got = ck.fit(TABLE, form="hh2011", fixed={"nu": 0.4})
        for name in ("H1", "H2", "mu"):
            self.assertTrue(close(got.parameters[name]["value"], want["parameters"][name]["value"], 1e-9), name)
            self.assertTrue(close(got.parameters[name]["sigma"], want["parameters"][name]["sigma"], 1e-6), name)
        self.assertTrue(got.parameters["nu"]["fixed"])
        self.assertEqual(got.correlation.shape, (3, 3))
        # the same table as arrays
        with open(TABLE) as f:
            lines = [line.strip().split(",") for line in f if line.strip() and not line.startswith("#")]
        header, values = lines[0], np.array(lines[1:], dtype=float)
        columns = {name: values[:, k] for k, name in enumerate(header)}
        again = ck.fit(columns, form="hh2011", fixed={"nu": 0.4})
        self.assertTrue(close(again.law.coefficient_1, got.law.coefficient_1, 1e-12))
        # its JSON is what --fit reads
        with tempfile.TemporaryDirectory() as tmp:
            path = os.path.join(tmp, "fit.json")
            with open(path, "w") as f:
                f.write(got.to_json())
            law, strength = ck.load_fit(path)
            self.assertTrue(close(law.coefficient_2, got.law.coefficient_2, 1e-15))
            self.assertIsNone(strength)
            scaled = cli("scale", "--fit", path, "--impactor-radius", 0.1, "--impactor-density", 2700, "--velocity",
                         2000, "--gravity", 1.4e-4, "--target-density", 1300, "--strength", 0.05)
            self.assertTrue(close(scaled["crater_radius"],
                                  ck.crater_radius(law, 0.1, 2700, 2000, 1300, 1.4e-4, 0.05)))
        # the fit's covariance carried into an age, as `age --fit --samples --seed`
        with tempfile.TemporaryDirectory() as tmp:
            path = os.path.join(tmp, "fit.json")
            with open(path, "w") as f:
                f.write(got.to_json())
            want = cli("age", COUNTS, "--fit", path, "--cohesion", 0.05, "--samples", 200, "--seed", 3)["ages"][0]
            laws = ck.sample_laws(path, samples=200, seed=3)
            self.assertEqual(len(laws), 200)
            counts = ck.read_counts(COUNTS)
            spread = ck.model_age_spread(counts, ck.Production(got.law, cohesion=0.05), laws)
            self.assertTrue(close(spread["law_median"][1], want["scaling_law_uncertainty"]["median_yr"]["p50"]))
            self.assertTrue(close(spread["total_median"], want["total_uncertainty"]["median_yr"]))
            self.assertTrue(close(spread["total_sigma1"][0], want["total_uncertainty"]["sigma1_yr"][0]))
        with self.assertRaisesRegex(ValueError, "column 'velocity'"):
            ck.fit({k: v for k, v in columns.items() if k != "velocity"})


    def test_grouped_fit_and_its_rate_spread_match_the_program(self):
        table = os.path.join(DATA, "examples", "radii_groups_example.csv")
        want = cli("fit", table, "--form", "hh2011", "--fix", "nu=0.4")
        got = ck.fit_groups(table, form="hh2011", fixed={"nu": 0.4})
        self.assertEqual(got["group_by"], want["group_by"])
        self.assertEqual(len(got["groups"]), len(want["groups"]))
        for g, w in zip(got["groups"], want["groups"]):
            self.assertEqual(g["key"], w["group"])
            self.assertEqual(g["regimes"], w["regime_counts"])
            for name in ("H1", "H2", "mu"):
                self.assertTrue(close(g["fit"].parameters[name]["value"], w["fit"]["parameters"][name]["value"],
                                      1e-9), name)
        self.assertEqual(len(ck.fit_groups(table, form="hh2011", fixed={"nu": 0.4}, group_by=[])["groups"]), 1)
        with self.assertRaisesRegex(ValueError, "colour"):
            ck.fit_groups(table, group_by="colour")
        # a group's law from the grouped JSON, and the law's uncertainty in relative rates as
        # `rates --fit --group --samples --seed`
        with tempfile.TemporaryDirectory() as tmp:
            path = os.path.join(tmp, "fit.json")
            with open(path, "w") as f:
                f.write(got["json"])
            group = "friction=0.8,porosity=0.5,resolution=18"
            law, _ = ck.load_fit(path, group=group)
            self.assertTrue(close(law.coefficient_1, got["groups"][1]["fit"].law.coefficient_1, 1e-15))
            want = cli("rates", "--fit", path, "--group", group, "--body", "ryugu", "--cohesion", "0.05,1",
                       "--diameters", "22,36", "--samples", 300, "--seed", 5)
            laws = ck.sample_laws(path, samples=300, seed=5, group=group)
            weak, strong = (ck.Production(law, cohesion=y, body="ryugu") for y in (0.05, 1.0))
            diameters = np.array([22.0, 36.0])
            spread = ck.relative_rate_spread(weak, strong, laws, diameters)
            checked = 0
            for row in want["rows"]:
                if row["cohesion"] != 1.0:
                    continue
                i = list(diameters).index(row["crater_diameter"])
                u = row["scaling_law_uncertainty"]
                for k, q in enumerate(("p16", "p50", "p84")):
                    self.assertTrue(close(spread["ratio"][k][i], u["relative_rate"][q], 1e-12), q)
                    self.assertTrue(close(spread["impactor_radius_b"][k][i], u["impactor_radius"][q], 1e-12), q)
                    self.assertTrue(close(spread["rate_b"][k][i] * 1e6, u["production_rate_per_km2_per_yr"][q],
                                          1e-12), q)
                checked += 1
            self.assertEqual(checked, 2)
            self.assertTrue(np.all(spread["ratio"][0] < spread["ratio"][2]))


class Chronology(unittest.TestCase):
    def test_bodies_and_populations(self):
        self.assertEqual(ck.body_names(), ["bennu", "ryugu"])
        ryugu = ck.load_body("ryugu")
        self.assertEqual((ryugu.name, ryugu.mean_radius, ryugu.bulk_density), ("Ryugu", 448.0, 1190.0))
        self.assertIn("main_belt", ryugu.regions)
        self.assertIn("power_law_q4", ck.population_names())
        q4 = ck.power_law_population(-4.0)
        np.testing.assert_allclose(q4.cumulative_number([1.0, 2.0, 10.0]), [1.0, 2.0 ** -3, 1e-3], rtol=1e-14)
        np.testing.assert_allclose(q4.differential_number(2.0), 3 * 2.0 ** -4, rtol=1e-14)
        belt = ck.load_population("main_belt_approx_bottke2005")
        n = belt.cumulative_number(np.geomspace(belt.minimum_radius * 1.01, belt.maximum_radius * 0.99, 20))
        self.assertTrue(np.all(np.diff(n) < 0))

    def test_production_and_relative_rates_match_the_program(self):
        law = ck.law("jutzi2022_ryugu")
        want = cli("rates", "--params", "jutzi2022_ryugu", "--body", "ryugu", "--cohesion", "0.05,1", "--diameters",
                   "22,36")
        weak, strong = (ck.Production(law, cohesion=y, body="ryugu") for y in (0.05, 1.0))
        diameters = np.array([22.0, 36.0])
        rates = {0.05: weak.rate(diameters), 1.0: strong.rate(diameters)}
        radii = {0.05: weak.impactor_radius(diameters), 1.0: strong.impactor_radius(diameters)}
        relative = ck.relative_rate(weak, strong, diameters)
        for row in want["rows"]:
            i = list(diameters).index(row["crater_diameter"])
            y = row["cohesion"]
            self.assertTrue(close(rates[y][i] * 1e6, row["production_rate_per_km2_per_yr"], 1e-12))
            self.assertTrue(close(radii[y][i], row["impactor_radius"], 1e-12))
            if y == 1.0:
                self.assertTrue(close(relative["ratio"][i], row["relative_rate"], 1e-12))
        self.assertEqual(weak.mean_speed, ck.load_body("ryugu").regions["main_belt"]["impact_speed"])
        self.assertTrue(np.all(weak.differential_rate(diameters) > 0))

    def test_counts_and_ages_match_the_program(self):
        counts = ck.read_counts(COUNTS)
        self.assertEqual(len(counts), 60)
        self.assertAlmostEqual(counts.area, 0.8e6)
        want = cli("age", COUNTS, "--params", "jutzi2022_ryugu", "--body", "ryugu", "--cohesion", "0,0.05,1")
        law = ck.law("jutzi2022_ryugu")
        for row in want["ages"]:
            age = ck.model_age(counts, ck.Production(law, cohesion=row["cohesion"], body="ryugu"))
            self.assertTrue(close(age.median, row["median_yr"], 1e-12), (age.median, row["median_yr"]))
            self.assertTrue(close(age.sigma1[0], row["sigma1_yr"][0], 1e-12))
            self.assertTrue(close(age.cumulative_fit_age, row["cumulative_fit_age_yr"], 1e-12))
            self.assertEqual(age.craters_in_range, row["craters_in_range"])
            self.assertEqual(age.age_grid.shape, age.density.shape)
        # counts written by Python read back exactly, and date the same
        with tempfile.TemporaryDirectory() as tmp:
            path = os.path.join(tmp, "unit.csv")
            ck.write_counts(counts, path)
            back = ck.read_counts(path)
            np.testing.assert_array_equal(back.diameters, counts.diameters)
            made = ck.CraterCounts(area=counts.area, diameters=counts.diameters)
            production = ck.Production(law, cohesion=0.05)
            self.assertEqual(ck.model_age(made, production).median, ck.model_age(back, production).median)
            binned = ck.CraterCounts(area=2.7e6, bin_diameters=[20.0, 40.0], cumulative_counts=[77.0, 10.0])
            self.assertTrue(binned.binned)
            ck.write_counts(binned, path)
            np.testing.assert_array_equal(ck.read_counts(path).cumulative_counts, [77.0, 10.0])
        with self.assertRaisesRegex(ValueError, "fraction"):
            ck.CraterCounts(area=1e6, diameters=[10.0, 20.0], fractions=[1.0, 1.5])

    def test_fraction_conventions_and_craterstats_formats_match_the_program(self):
        law = ck.law("jutzi2022_ryugu")
        counts = ck.read_counts(COUNTS)
        fractions = np.where(np.arange(len(counts)) % 3 == 0, 0.5, 1.0)
        partial = ck.CraterCounts(area=counts.area, diameters=counts.diameters, fractions=fractions)
        production = ck.Production(law, cohesion=0.05)
        with tempfile.TemporaryDirectory() as tmp:
            path = os.path.join(tmp, "partial.csv")
            ck.write_counts(partial, path)
            for convention in ("weight", "whole"):
                want = cli("age", path, "--params", "jutzi2022_ryugu", "--cohesion", 0.05, "--fractions", convention)
                got = ck.model_age(partial, production, fractions=convention)
                self.assertTrue(close(got.median, want["ages"][0]["median_yr"]), convention)
                self.assertEqual(got.craters_in_range, want["ages"][0]["craters_in_range"])
            self.assertEqual(ck.model_age(partial, production, fractions="whole").craters_in_range, len(counts))
            # a craterstats binned file: the bins' craters from D up, the last bin closed by an empty one
            binned = os.path.join(tmp, "unit.binned")
            with open(binned, "w") as f:
                f.write("area = 0.8\ntable = {diameter,frequency\n0.010 30\n0.020 20\n0.040 10\n0.080 0\n}\n")
            b = ck.read_counts(binned)
            np.testing.assert_array_equal(b.cumulative_counts, [60, 30, 10, 0])
            want = cli("age", binned, "--params", "jutzi2022_ryugu", "--cohesion", 0.05)
            self.assertTrue(close(ck.model_age(b, production).median, want["ages"][0]["median_yr"]))
        # a published chronology system instead of the scaling law, with craterstats' conventions
        unit = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "chronology", "data",
                            "synthetic_lunar_unit.diam")
        moon = ck.load_chronology_system("moon_neukum2001")
        self.assertIn("moon_neukum2001", ck.chronology_system_names())
        self.assertTrue(close(float(moon.n1(3e9)), 5.44e-14 * math.expm1(6.93 * 3) + 8.38e-4 * 3, 1e-13))
        np.testing.assert_allclose(moon.cumulative_density(1000.0, [1e9, 3e9]), moon.n1([1e9, 3e9]), rtol=1e-13)
        want = cli("age", unit, "--chronology", "moon_neukum2001", "--min-diameter", 200, "--max-diameter", 1000,
                   "--fractions", "whole", "--prior", "density")
        got = ck.model_age(ck.read_counts(unit), moon, min_diameter=200, max_diameter=1000, fractions="whole",
                           prior="density")
        self.assertTrue(close(got.median, want["ages"][0]["median_yr"]))
        self.assertTrue(math.isclose(got.median / 1e9, 0.81299883, rel_tol=6e-3))  # craterstats 3.6.10
        # a system whose production function is Hartmann's table (tabular incremental root-2)
        mars = ck.load_chronology_system("mars_hartmann2005")
        self.assertIn("mars_hartmann_daubar2016", ck.chronology_system_names())
        self.assertEqual(mars.production_form, "tabular_incremental_root2")
        self.assertEqual((len(mars.incremental_density), mars.index_1km, len(mars.production_coefficients)),
                         (36, 16, 0))
        self.assertEqual(moon.production_form, "polynomial")
        # craterstats 3.6.10: Productionfn('Mars, Hartmann (2005)').C(3.7, Chronologyfn(...).a0(3.0))
        self.assertTrue(close(float(mars.cumulative_density(3700.0, 3e9)), 1.5021119133634729e-4, 1e-12))
        want = cli("age", unit, "--chronology", "mars_hartmann2005", "--min-diameter", 200, "--max-diameter", 1000,
                   "--fractions", "whole", "--prior", "density")
        got = ck.model_age(ck.read_counts(unit), mars, min_diameter=200, max_diameter=1000, fractions="whole",
                           prior="density")
        self.assertTrue(close(got.median, want["ages"][0]["median_yr"]))
        self.assertTrue(math.isclose(got.median / 1e9, 1.7215997, rel_tol=6e-3))  # craterstats 3.6.10
        with self.assertRaisesRegex(ValueError, "allowed: weight, whole"):
            ck.model_age(partial, production, fractions="half")


TINY_IMPACT = """[problem]
name = "tiny-impact"
setup = "impact"
[impact]
projectile_model = "resolved"
projectile_density = 1300.0
projectile_mass = 5450.0
impact_speed = 50.0
A_low = 0.27e6
domain_radius = 5.0
particle_spacing = 0.5
t_transition = 0.01
[run]
end_time = 0.002
gravity = [0.0, 0.0, -1.0]
[kernel]
max_smoothing_length = 1.8
[output]
snapshot_times = [0.0]
"""


class Snapshots(unittest.TestCase):
    def test_read_and_measure_like_the_program(self):
        with tempfile.TemporaryDirectory() as tmp:
            config = os.path.join(tmp, "tiny.toml")
            with open(config, "w") as f:
                f.write(TINY_IMPACT)
            run = os.path.join(tmp, "run")
            subprocess.run([CK, "simulate", config, "--out", run, "--threads", "1", "--quiet"], check=True,
                           capture_output=True)
            snapshot = os.path.join(run, "snap_000000.h5")
            fields, attributes = ck.read_snapshot(snapshot)
            # Every configuration value the run used, defaults included, one "key = value" line each.
            lines = attributes["configuration"].splitlines()
            self.assertIn("impact.projectile_mass = 5450", lines)
            self.assertIn('problem.name = "tiny-impact"', lines)
            self.assertEqual(attributes["craterkit_version"], ck.__version__)
            self.assertEqual(attributes["setup"], "impact")
            n = len(fields["x"])
            self.assertGreater(n, 100)
            for name in ("id", "material", "y", "z", "vx", "mass", "density", "pressure"):
                self.assertEqual(len(fields[name]), n, name)
            self.assertEqual(fields["id"].dtype, np.uint64)
            self.assertTrue(np.all(fields["mass"] > 0))
            want = json.loads(subprocess.run([CK, "measure", snapshot, "--json"], check=True, capture_output=True,
                                             text=True).stdout)
            got = ck.measure_crater(snapshot)
            self.assertEqual(got, want)
            with self.assertRaisesRegex(ValueError, "azimuths 6"):
                ck.measure_crater(snapshot, azimuths=6)


if __name__ == "__main__":
    unittest.main(verbosity=2)
