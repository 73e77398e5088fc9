#!/usr/bin/env python3
"""Run a study of impact simulations: variants of one configuration, then a table of their craters.

Usage:
  impact_study.py BASE.toml OUT_DIR NAME[:KEY=VALUE[;KEY=VALUE...]] ... [--jobs N] [--threads T]
                  [--craterkit PATH] [--dry-run]

Each NAME is one run in OUT_DIR/NAME: the base configuration with the given overrides, written to
OUT_DIR/NAME/config.toml and run with `craterkit simulate ... --json`. KEY is a dotted configuration key
(`impact.inner_spacing=0.04`, `run.gravity=[0,0,-1.4e-2]`, `impact.t_transition=0.2`) or, with the prefix
`target.`, a key of the target material's file (`target.strength.cohesion=0.5`,
`target.strength.friction_coefficient=1.0`): the material is then copied to OUT_DIR/NAME/target.toml with
the change and the run points at it. VALUE is TOML (a number, a quoted string, an array).

Runs already finished (OUT_DIR/NAME/summary.json complete) are skipped; a run with a checkpoint but no
summary is resumed (`--resume`), so the study can be killed and started again. --jobs runs that many at
a time (each with --threads threads, default 1). At the end OUT_DIR/results.csv lists every run: name,
overrides, crater radius and its uncertainty (m), depth (m), whether the run stopped because growth
ended, when growth ended and the radius then (also for runs that went on, `crater.stop_when_grown=false`;
empty if it never did), end time (s), particles, steps, wall seconds and particle updates per second.

Only the Python standard library is needed (tomllib: Python >= 3.11).
"""
import csv
import json
import math
import os
import subprocess
import sys
import tomllib
from concurrent.futures import ThreadPoolExecutor

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(os.path.dirname(HERE))


def toml_value(v):
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, int):
        return str(v)
    if isinstance(v, float):
        if math.isinf(v):
            return "inf" if v > 0 else "-inf"
        return repr(v)
    if isinstance(v, str):
        return json.dumps(v)
    if isinstance(v, list):
        return "[" + ", ".join(toml_value(x) for x in v) + "]"
    raise ValueError(f"cannot write {v!r} as a TOML value")


def is_table_array(v):
    return isinstance(v, list) and v and all(isinstance(x, dict) for x in v)


def write_table(lines, path, table):
    """Scalars first, then sub-tables and arrays of tables (TOML needs that order)."""
    for k, v in table.items():
        if not isinstance(v, dict) and not is_table_array(v):
            lines.append(f"{k} = {toml_value(v)}")
    for k, v in table.items():
        name = f"{path}.{k}" if path else k
        if isinstance(v, dict):
            lines.append("")
            lines.append(f"[{name}]")
            write_table(lines, name, v)
        elif is_table_array(v):
            for item in v:
                lines.append("")
                lines.append(f"[[{name}]]")
                write_table(lines, name, item)


def dumps(document):
    lines = []
    write_table(lines, "", document)
    return "\n".join(lines).lstrip("\n") + "\n"


def set_key(document, dotted, value, what):
    keys = dotted.split(".")
    node = document
    for k in keys[:-1]:
        node = node.setdefault(k, {})
        if not isinstance(node, dict):
            raise SystemExit(f"{what}: {k} in {dotted} is not a table")
    node[keys[-1]] = value


def parse_override(text, run):
    key, sep, value = text.partition("=")
    if not sep or not key.strip():
        raise SystemExit(f"run {run}: override {text!r} is not KEY=VALUE")
    try:
        parsed = tomllib.loads(f"v = {value.strip()}")["v"]
    except tomllib.TOMLDecodeError as e:
        raise SystemExit(f"run {run}: value of {key.strip()} ({value.strip()!r}) is not TOML: {e}")
    return key.strip(), parsed


def material_file(name_or_path, base_dir):
    for candidate in (name_or_path, os.path.join(base_dir, name_or_path)):
        if os.path.isfile(candidate):
            return candidate
    data = os.environ.get("CRATERKIT_DATA_DIR", os.path.join(REPO, "data"))
    path = os.path.join(data, "materials", name_or_path + ".toml")
    if not os.path.isfile(path):
        raise SystemExit(f"target material {name_or_path!r}: neither a file nor {path}")
    return path


def prepare(base, base_path, out_dir, spec):
    name, _, overrides_text = spec.partition(":")
    if not name or "/" in name:
        raise SystemExit(f"run name {name!r}: must be non-empty and contain no '/'")
    overrides = [parse_override(o, name) for o in overrides_text.split(";") if o.strip()]
    run_dir = os.path.join(out_dir, name)
    os.makedirs(run_dir, exist_ok=True)
    config = json.loads(json.dumps(base))  # deep copy
    config.setdefault("problem", {})["name"] = name
    target = {}
    for key, value in overrides:
        if key.startswith("target."):
            target[key[len("target."):]] = value
        else:
            set_key(config, key, value, f"run {name}")
    if target:
        impact = config.setdefault("impact", {})
        source = material_file(impact.get("target_material", "basalt_matrix_ryugu"),
                               os.path.dirname(os.path.abspath(base_path)))
        with open(source, "rb") as f:
            material = tomllib.load(f)
        for key, value in target.items():
            set_key(material, key, value, f"run {name}")
        material_path = os.path.join(run_dir, "target.toml")
        write_atomically(material_path, dumps(material))
        impact["target_material"] = os.path.abspath(material_path)
    config_path = os.path.join(run_dir, "config.toml")
    write_atomically(config_path, dumps(config))
    return name, overrides_text, run_dir, config_path


def write_atomically(path, text):
    tmp = path + ".tmp"
    with open(tmp, "w") as f:
        f.write(text)
    os.replace(tmp, path)


def read_summary(run_dir):
    try:
        with open(os.path.join(run_dir, "summary.json")) as f:
            return json.load(f)
    except (OSError, json.JSONDecodeError):
        return None


def run_one(craterkit, threads, run):
    name, _, run_dir, config_path = run
    if read_summary(run_dir) is not None:
        print(f"{name}: done before, skipped", flush=True)
        return
    out = os.path.join(run_dir, "run")
    command = [craterkit, "simulate", config_path, "--out", out, "--threads", str(threads), "--json"]
    if os.path.isfile(os.path.join(out, "checkpoint.h5")):
        command.append("--resume")
    print(f"{name}: {' '.join(command)}", flush=True)
    with open(os.path.join(run_dir, "summary.json.tmp"), "w") as stdout, \
            open(os.path.join(run_dir, "log.txt"), "a") as stderr:
        status = subprocess.call(command, stdout=stdout, stderr=stderr)
    if status == 0:
        os.replace(os.path.join(run_dir, "summary.json.tmp"), os.path.join(run_dir, "summary.json"))
    print(f"{name}: exit status {status} (log: {os.path.join(run_dir, 'log.txt')})", flush=True)


def main(argv):
    args, jobs, threads, dry_run = [], 1, 1, False
    craterkit = os.path.join(REPO, "build", "release", "apps", "craterkit")
    it = iter(argv[1:])
    for a in it:
        if a == "--jobs":
            jobs = int(next(it))
        elif a == "--threads":
            threads = int(next(it))
        elif a == "--craterkit":
            craterkit = next(it)
        elif a == "--dry-run":
            dry_run = True
        elif a in ("-h", "--help"):
            print(__doc__)
            return 0
        else:
            args.append(a)
    if len(args) < 3:
        print(__doc__)
        return 2
    base_path, out_dir, specs = args[0], args[1], args[2:]
    with open(base_path, "rb") as f:
        base = tomllib.load(f)
    runs = [prepare(base, base_path, out_dir, s) for s in specs]
    if not dry_run:
        with ThreadPoolExecutor(max_workers=jobs) as pool:
            list(pool.map(lambda r: run_one(craterkit, threads, r), runs))
    fields = ["name", "overrides", "crater_radius_m", "crater_radius_uncertainty_m", "depth_m",
              "growth_ended", "growth_end_time_s", "growth_end_radius_m", "time_s", "particles", "steps", "wall_seconds", "particle_updates_per_second"]
    rows = []
    for name, overrides, run_dir, _ in runs:
        s = read_summary(run_dir) or {}
        rows.append({"name": name, "overrides": overrides,
                     "crater_radius_m": s.get("crater_radius", ""),
                     "crater_radius_uncertainty_m": s.get("crater_radius_uncertainty", ""),
                     "depth_m": s.get("crater_depth", ""), "growth_ended": s.get("crater_growth_ended", ""),
                     "growth_end_time_s": s.get("crater_growth_end_time") or "",
                     "growth_end_radius_m": s.get("crater_growth_end_radius") or "",
                     "time_s": s.get("time", ""), "particles": s.get("particles", ""),
                     "steps": s.get("steps", ""), "wall_seconds": s.get("wall_seconds", ""),
                     "particle_updates_per_second": s.get("particle_updates_per_second", "")})
    tmp = os.path.join(out_dir, "results.csv.tmp")
    with open(tmp, "w", newline="") as f:
        writer = csv.DictWriter(f, fieldnames=fields)
        writer.writeheader()
        writer.writerows(rows)
    os.replace(tmp, os.path.join(out_dir, "results.csv"))
    for r in rows:
        radius = r["crater_radius_m"]
        text = f"{radius:.3f} +- {r['crater_radius_uncertainty_m']:.3f} m" if radius != "" else "not finished"
        print(f"{r['name']:>16}  {text}  ({r['overrides']})")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
