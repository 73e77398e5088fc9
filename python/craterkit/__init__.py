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
    relative_rate_spread,
    sample_laws,
    strength_limit_radius,
    write_counts,
)
from . import _craterkit

__version__ = "@PROJECT_VERSION@"

__all__ = [
    "AgeEstimate", "Body", "ChronologySystem", "ConstantSet", "CraterCounts", "FitResult", "Population", "Production", "ScalingLaw",
    "body_names", "chronology_system_names", "constant_set_names", "crater_radius", "data_directory", "fit", "fit_groups", "gravity_limit_radius",
    "impact_velocity", "impactor_radius", "law", "load_body", "load_chronology_system", "load_constant_set", "load_fit", "load_population",
    "measure_crater", "model_age", "model_age_spread", "population_names", "power_law_population", "read_counts", "read_snapshot", "relative_rate", "relative_rate_spread", "sample_laws",
    "strength_limit_radius", "write_counts",
]


def fit_groups(table, form="holsapple", fixed=None, group_by=None, require_growth_ended=False, starts=12,
               seed=20221):
    """One Ceres fit per group of a sweep table's grouping columns, as `craterkit fit --group-by`.

    table: the path of a radii CSV with grouping columns (friction, porosity, resolution, ...; `craterkit sweep`
    writes them). group_by: the columns to fit separately (default: every grouping column; [] for one fit over
    all rows). require_growth_ended: leave out the rows whose growth did not end. Returns a dict: 'groups' (a
    list of dicts with 'key' {column: value as written}, 'label', 'lines', 'cohesions', 'strength_range',
    'fit' (a FitResult, or None with the reason in 'not_fitted'), 'regimes' {gravity, transitional,
    strength}), 'group_by', 'pooled' {column: values fitted together}, 'excluded', 'notes', and 'json' (what
    `craterkit fit --out` writes; load_fit(path, group='KEY=VALUE,...') reads a group's law from it).
    """
    if group_by is not None:
        group_by = [group_by] if isinstance(group_by, str) else list(group_by)
    return _craterkit._fit_groups(_os.fspath(table), form, dict(fixed or {}), group_by,
                                  bool(require_growth_ended), int(starts), int(seed))


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
