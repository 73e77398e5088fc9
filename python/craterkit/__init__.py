"""craterkit: crater scaling and crater chronology for small, low-gravity bodies.

The point-source scaling law (forward and inverse, both forms, the published constant sets and the Ceres fit)
and the chronology (bodies, impactor populations, crater production, relative rates, crater counts and model
ages) of the craterkit C++ libraries. Functions of one impact or one crater size take NumPy arrays or numbers
and broadcast like NumPy ufuncs. Bad input raises ValueError with craterkit's message. SI units throughout:
metres, kg/m^3, m/s, Pa, years. See docs/python.md.
"""

import os as _os

from ._craterkit import (
    AgeEstimate,
    Body,
    ChronologySystem,
    ConstantSet,
    CraterCounts,
    FitResult,
    Population,
    Production,
    ScalingLaw,
    body_names,
    chronology_system_names,
    constant_set_names,
    crater_radius,
    data_directory,
    gravity_limit_radius,
    impact_velocity,
    impactor_radius,
    load_body,
    load_chronology_system,
    load_constant_set,
    load_fit,
    load_population,
    measure_crater,
    model_age,
    model_age_spread,
    population_names,
    power_law_population,
    read_counts,
    read_snapshot,
    relative_rate,
    sample_laws,
    strength_limit_radius,
    write_counts,
)
from . import _craterkit

__version__ = "@PROJECT_VERSION@"

__all__ = [
    "AgeEstimate", "Body", "ChronologySystem", "ConstantSet", "CraterCounts", "FitResult", "Population", "Production", "ScalingLaw",
    "body_names", "chronology_system_names", "constant_set_names", "crater_radius", "data_directory", "fit", "gravity_limit_radius",
    "impact_velocity", "impactor_radius", "law", "load_body", "load_chronology_system", "load_constant_set", "load_fit", "load_population",
    "measure_crater", "model_age", "model_age_spread", "population_names", "power_law_population", "read_counts", "read_snapshot", "relative_rate", "sample_laws",
    "strength_limit_radius", "write_counts",
]


def law(name_or_path):
    """The ScalingLaw of a shipped constant set ('jutzi2022_ryugu') or of a constant-set .toml file."""
    return load_constant_set(name_or_path).law


def fit(table, form="holsapple", fixed=None, shared_strength=False, starts=12, seed=20221):
    """Fits the scaling law to a table of craters with Ceres; returns a FitResult.

    table: the path of a radii CSV (as `craterkit fit` reads), or a mapping of equal-length arrays with the
    columns impactor_radius, impactor_density, velocity, target_density, gravity, strength, crater_radius and
    optionally crater_radius_sigma. form: 'holsapple' (K1, K2) or 'hh2011' (H1, H2). fixed: {name: value} for
    the parameters held fixed (K1, K2 or H1, H2, mu, nu, Y). shared_strength: fit one strength Y for all rows.
    """
    if not isinstance(table, (str, bytes, _os.PathLike)):
        table = dict(table)
    return _craterkit._fit(table, form, dict(fixed or {}), bool(shared_strength), int(starts), int(seed))
