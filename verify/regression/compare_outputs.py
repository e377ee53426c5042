#!/usr/bin/env python3
"""Runs a fixed list of commands with two `gearimpact` programs and compares what they write.

    verify/regression/compare_outputs.py BASE_PROGRAM NEW_PROGRAM [--keep DIR] [--only NAME ...]

Each command runs once with each program, in a folder of its own under a temporary folder (or
--keep DIR, which is kept): the files it writes, and its standard output where that is an output
(the JSON summaries of `simulate`, `modes`, ...), are then compared byte for byte. Where the bytes
differ, a CSV file gets the largest relative difference per numeric column, |a - b| / max(|a|, |b|),
and a JSON file the same per numeric leaf; a text cell or a row count that differs is named.
Exit status 0 when every output is the same to the byte, 1 otherwise, 2 when a command fails
with one program and not with the other.

The list covers what a refactor of the dynamics can change: the reproduction (its default),
every example run file (torsional and planar, series and samples), the paper's cases 1-3, the
adaptive integrator, the planar model (RK4 and Dormand-Prince, friction on both flanks, shafts,
a tacho, modifications, a fault, the Lagrangian force and the mesh damper, a friction law
whose f varies, a constant stiffness, a driver against a drag), a small steady sweep, `modes`, `ste`, `mesh-stiffness` and
`signals` on the rig's samples. It is not part of ctest: a run takes about a minute.
"""

import argparse
import json
import math
import os
import pathlib
import shutil
import subprocess
import sys
import re
import tempfile

REPO = pathlib.Path(__file__).resolve().parents[2]
EXAMPLES = REPO / "examples"
PAPER_DATA = REPO / "paper_data"

# Elastic bearings for a case that has none (the paper's cases): the planar model.
ELASTIC = [
    "--set", "bearings.kind=elastic",
    "--set", "bearings.stiffness_x1=1e8 N/m",
    "--set", "bearings.stiffness_x2=1e8 N/m",
]
SHAFTS = [
    "--set", "shafts.kind=elastic",
    "--set", "shafts.motor_inertia=2e-3 kg*m^2",
    "--set", "shafts.motor_stiffness=2e4 N*m/rad",
    "--set", "shafts.motor_damping=1 N*m*s/rad",
    "--set", "shafts.load_inertia=5e-3 kg*m^2",
    "--set", "shafts.load_stiffness=3e4 N*m/rad",
]

RELIEF = [
    "--set", "modifications.tip_relief1=10 um",
    "--set", "modifications.tip_relief_start1=43.2 mm",
    "--set", "modifications.tip_relief2=10 um",
    "--set", "modifications.tip_relief_start2=163.2 mm",
]


def ex(name):
    return str(EXAMPLES / name)


# (name, arguments, whether standard output is an output). Arguments name the output folder
# as "{out}"; a command reads an earlier command's file through "{out:NAME}/FILE".
COMMANDS = [
    ("reproduce", ["reproduce", "--out", "{out}/r", "--paper-data", str(PAPER_DATA)], False),
    ("case1", ["simulate", "--case", "1", "--out", "{out}/series.csv"], True),
    ("case2", ["simulate", "--case", "2", "--out", "{out}/series.csv"], True),
    ("case3", ["simulate", "--case", "3", "--out", "{out}/series.csv"], True),
    ("case2_adaptive",
     ["simulate", "--case", "2", "--integrator", "adaptive", "--out", "{out}/series.csv"], True),
    ("case3_samples",
     ["simulate", "--case", "3", "--sample-rate", "200 kHz", "--out", "{out}/samples.csv"], True),
    ("case1_point_samples",
     ["simulate", "--case", "1", "--sample-rate", "100 kHz", "--sample", "point",
      "--out", "{out}/samples.csv"], True),
    ("pair_23_67",
     ["simulate", "--case-file", ex("pair_23_67.toml"), "--every", "10",
      "--out", "{out}/series.csv"], True),
    ("spall_20_80",
     ["simulate", "--case-file", ex("spall_20_80.toml"), "--every", "10",
      "--out", "{out}/series.csv"], True),
    ("spall_20_80_samples",
     ["simulate", "--case-file", ex("spall_20_80.toml"), "--sample-rate", "50 kHz",
      "--out", "{out}/samples.csv"], True),
    ("pair_25_53_samples",
     ["simulate", "--case-file", ex("pair_25_53.toml"), "--t-end", "50 ms", "--sample-rate",
      "25.6 kHz", "--out", "{out}/samples.csv"], True),
    ("rig_series",
     ["simulate", "--case-file", ex("rig_17_38.toml"), "--t-end", "20 ms",
      "--out", "{out}/series.csv"], True),
    ("rig_samples",
     ["simulate", "--case-file", ex("rig_17_38.toml"), "--sample-rate", "51.2 kHz",
      "--out", "{out}/samples.csv"], True),
    ("rig_point_samples",
     ["simulate", "--case-file", ex("rig_17_38.toml"), "--t-end", "20 ms", "--sample-rate",
      "51.2 kHz", "--sample", "point", "--out", "{out}/samples.csv"], True),
    ("rig_dopri5_samples",
     ["simulate", "--case-file", ex("rig_17_38.toml"), "--integrator", "dopri5",
      "--dt", "4 us", "--sample-rate", "51.2 kHz", "--out", "{out}/samples.csv"], True),
    ("rig_tacho",
     ["simulate", "--case-file", ex("rig_17_38.toml"), "--t-end", "30 ms",
      "--set", "tacho.pulses_per_revolution=4", "--tacho-out", "{out}/tacho.csv",
      "--sample-rate", "20 kHz", "--out", "{out}/samples.csv"], True),
    ("rig_shafts",
     ["simulate", "--case-file", ex("rig_17_38.toml"), "--t-end", "20 ms", *SHAFTS,
      "--out", "{out}/series.csv"], True),
    # Rattle on bearings: impacts on both flanks, friction on the coast flank too.
    ("planar_case1_friction",
     ["simulate", "--case", "1", *ELASTIC, "--friction", "0.05", "--t-end", "10 ms",
      "--out", "{out}/series.csv"], True),
    ("planar_case3_friction",
     ["simulate", "--case", "3", *ELASTIC, "--friction", "0.05", "--t-end", "10 ms",
      "--sample-rate", "100 kHz", "--out", "{out}/samples.csv"], True),
    ("planar_case2_dopri5",
     ["simulate", "--case", "2", *ELASTIC, "--integrator", "dopri5", "--t-end", "10 ms",
      "--out", "{out}/series.csv"], True),
    ("planar_spall",
     ["simulate", "--case-file", ex("spall_20_80.toml"), *ELASTIC, "--t-end", "5 ms",
      "--every", "10", "--out", "{out}/series.csv"], True),
    # Tip relief: each pair touches by its own penetration (gaps, the reliefs' kinks).
    ("relief_case2",
     ["simulate", "--case", "2", *RELIEF, "--t-end", "10 ms", "--every", "10",
      "--out", "{out}/series.csv"], True),
    ("planar_relief_case2",
     ["simulate", "--case", "2", *RELIEF, *ELASTIC, "--friction", "0.05", "--t-end", "5 ms",
      "--every", "10", "--out", "{out}/series.csv"], True),
    # The mesh's options on bearings: the Lagrangian force with the viscous mesh damper; a
    # friction law whose f varies, smoothed, with D's stiffness frozen at the pitch pair; a
    # constant stiffness with Hertz's K; a kinematic driver against a drag.
    ("planar_case2_lagrangian_damper",
     ["simulate", "--case", "2", *ELASTIC, "--set", "model.mesh_force=lagrangian",
      "--set", "model.mesh_damping_ratio=0.05", "--t-end", "5 ms",
      "--out", "{out}/series.csv"], True),
    ("planar_case1_benedict_kelley",
     ["simulate", "--case", "1", *ELASTIC, "--set", "model.friction_law=benedict-kelley",
      "--set", "model.lubricant_viscosity=30 cP", "--set", "model.surface_roughness=0.5 um",
      "--set", "model.friction_smoothing_speed=0.01 m/s",
      "--set", "model.damping_stiffness=pitch-pair-at-impact", "--t-end", "10 ms",
      "--out", "{out}/series.csv"], True),
    ("planar_case3_constant_hertz",
     ["simulate", "--case", "3", *ELASTIC, "--set", "model.damping_stiffness=hertz",
      "--set", "model.mesh_stiffness=constant", "--set", "model.constant_mesh_stiffness=3e8 N/m",
      "--friction", "0.05", "--t-end", "10 ms", "--out", "{out}/series.csv"], True),
    ("planar_case1_driver_drag",
     ["simulate", "--case", "1", *ELASTIC, "--set", "torque1.kind=prescribed-speed",
      "--set", "torque1.mean_speed=477.4648292756860 rpm", "--set", "torque1.orders=2",
      "--set", "torque1.speed_amplitudes=20 rad/s", "--set", "torque1.phases=0 deg",
      "--set", "torque2.kind=drag", "--set", "torque2.drag_constant=0.5 N*m",
      "--set", "torque2.drag_viscous=0.001 N*m*s/rad", "--friction", "0.05",
      "--t-end", "10 ms", "--out", "{out}/series.csv"], True),
    ("sweep_case1",
     ["sweep", "1", "--vary", "initial.w1", "--from", "2000 rad/s", "--to", "4000 rad/s",
      "--points", "3", "--set", "model.friction_coefficient=0", "--threads", "1",
      "--no-plots", "--out", "{out}/sweep"], False),
    ("modes_rig",
     ["modes", ex("rig_17_38.toml"), "--no-plots", "--out", "{out}/modes"], True),
    ("modes_pair",
     ["modes", ex("pair_23_67.toml"), "--no-plots", "--out", "{out}/modes"], True),
    ("ste_tip_relief",
     ["ste", ex("tip_relief_20_80.toml"), "--torque", "100 N*m", "--no-plots",
      "--out", "{out}/ste"], True),
    ("ste_cracked",
     ["ste", ex("cracked_pinion.toml"), "--torque", "50 N*m", "--no-plots",
      "--out", "{out}/ste"], True),
    ("mesh_stiffness_cracked",
     ["mesh-stiffness", "--case-file", ex("cracked_pinion.toml")], True),
    ("mesh_stiffness_summary",
     ["mesh-stiffness", "--case-file", ex("cracked_pinion.toml"), "--summary"], True),
    ("signals_rig",
     ["signals", "{out:rig_samples}/samples.csv", "--column", "sensor_acceleration_m_per_s2",
      "--angle-column", "theta1_rad", "--teeth", "17", "--no-plots", "--out", "{out}/signals"],
     True),
]


def expand(args, out, root):
    result = []
    for a in args:
        if a.startswith("{out:"):
            name, rest = a[len("{out:"):].split("}", 1)
            # Relative to the command's own folder (its working folder), so that a path an
            # output echoes is the same text with both programs.
            a = "../" + name + rest
        result.append(a.replace("{out}", str(out)))
    return result


def run_all(program, root, only):
    """Runs every command with `program` into root/NAME; returns {name: exit status}."""
    status = {}
    for name, args, stdout_is_output in COMMANDS:
        if only and name not in only:
            continue
        out = root / name
        out.mkdir(parents=True, exist_ok=True)
        proc = subprocess.run([program, *expand(args, out, root)], capture_output=True,
                              cwd=out, check=False)
        if stdout_is_output:
            (out / "stdout.txt").write_bytes(proc.stdout)
        (out.parent / (name + ".stderr")).write_bytes(proc.stderr)
        status[name] = proc.returncode
    return status


def number(text):
    try:
        return float(text)
    except ValueError:
        return None


def relative(a, b):
    if a == b or (math.isnan(a) and math.isnan(b)):
        return 0.0
    scale = max(abs(a), abs(b))
    return math.inf if not math.isfinite(scale) else abs(a - b) / scale


def compare_csv(a, b):
    """Largest relative difference per numeric column; text cells and shapes that differ."""
    rows_a = a.decode().splitlines()
    rows_b = b.decode().splitlines()
    notes = []
    if len(rows_a) != len(rows_b):
        notes.append(f"rows {len(rows_a)} vs {len(rows_b)}")
    header = rows_a[0].split(",") if rows_a else []
    worst = {}
    text = set()
    for ra, rb in zip(rows_a, rows_b):
        ca, cb = ra.split(","), rb.split(",")
        if len(ca) != len(cb):
            notes.append("a row's cell count differs")
            break
        for i, (x, y) in enumerate(zip(ca, cb)):
            if x == y:
                continue
            nx, ny = number(x), number(y)
            col = header[i] if i < len(header) else str(i)
            if nx is None or ny is None:
                text.add(col)
                continue
            worst[col] = max(worst.get(col, 0.0), relative(nx, ny))
    notes += [f"{k}: {v:.3g}" for k, v in sorted(worst.items(), key=lambda kv: -kv[1])]
    notes += [f"{k}: text differs" for k in sorted(text)]
    return notes


def leaves(value, path=""):
    if isinstance(value, dict):
        for k, v in value.items():
            yield from leaves(v, f"{path}.{k}" if path else k)
    elif isinstance(value, list):
        for i, v in enumerate(value):
            yield from leaves(v, f"{path}[{i}]")
    else:
        yield path, value


def compare_json(a, b):
    try:
        ja, jb = json.loads(a), json.loads(b)
    except ValueError:
        return ["not JSON; bytes differ"]
    la, lb = dict(leaves(ja)), dict(leaves(jb))
    notes = [f"{k}: only in one" for k in sorted(set(la) ^ set(lb))]
    for k in sorted(set(la) & set(lb)):
        x, y = la[k], lb[k]
        if x == y:
            continue
        if isinstance(x, (int, float)) and isinstance(y, (int, float)):
            notes.append(f"{k}: {relative(float(x), float(y)):.3g}")
        else:
            notes.append(f"{k}: {x!r} vs {y!r}")
    return notes


# The reproduction's report states how long its parts took: not an output of the model.
TIMINGS = re.compile(rb"(Computed in|wall time:|CPU time:|cpu time:) *[0-9.]+ *s")


def without_timings(text):
    return TIMINGS.sub(rb"\1 _ s", text)


def compare_trees(base, new):
    """Returns [(relative path, notes)] of every file that differs or is in one tree only."""
    files_a = {p.relative_to(base) for p in base.rglob("*") if p.is_file()}
    files_b = {p.relative_to(new) for p in new.rglob("*") if p.is_file()}
    differences = []
    for rel in sorted(files_a | files_b):
        if rel.suffix == ".stderr":
            continue
        if rel not in files_a or rel not in files_b:
            differences.append((rel, ["only with the " + ("new" if rel in files_b else "base")]))
            continue
        a, b = (base / rel).read_bytes(), (new / rel).read_bytes()
        if rel.suffix == ".md":
            a, b = without_timings(a), without_timings(b)
        if a == b:
            continue
        if rel.suffix == ".csv":
            notes = compare_csv(a, b)
        elif rel.suffix == ".json" or rel.name == "stdout.txt":
            notes = compare_json(a, b)
        else:
            notes = ["bytes differ"]
        differences.append((rel, notes or ["bytes differ (same numbers)"]))
    return differences


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("base", help="the gearimpact program to compare against")
    parser.add_argument("new", help="the gearimpact program under test")
    parser.add_argument("--keep", help="write the outputs into this folder and keep them")
    parser.add_argument("--only", nargs="*", help="run only these commands (by name)")
    parser.add_argument("--list", action="store_true", help="list the commands and exit")
    args = parser.parse_args()
    if args.list:
        for name, argv, _ in COMMANDS:
            print(name + ": gearimpact " + " ".join(argv))
        return 0
    root = pathlib.Path(args.keep) if args.keep else pathlib.Path(tempfile.mkdtemp())
    if args.keep and root.exists() and any(root.iterdir()):
        print(f"compare_outputs: --keep {root} is not empty", file=sys.stderr)
        return 2
    try:
        status_a = run_all(os.path.abspath(args.base), root / "base", args.only)
        status_b = run_all(os.path.abspath(args.new), root / "new", args.only)
        failed = False
        for name in status_a:
            if status_a[name] != status_b[name]:
                failed = True
                print(f"{name}: exit status {status_a[name]} (base) vs {status_b[name]} (new)")
            elif status_a[name] != 0:
                print(f"{name}: both exit {status_a[name]} (see its .stderr)")
        differences = compare_trees(root / "base", root / "new")
        for rel, notes in differences:
            print(f"DIFFERS {rel}: " + "; ".join(notes[:12]) +
                  (f" (+{len(notes) - 12} more)" if len(notes) > 12 else ""))
        files = sum(1 for p in (root / "base").rglob("*") if p.is_file())
        print(f"{len(status_a)} commands, {files} files: "
              f"{'all the same to the byte' if not differences else str(len(differences)) + ' differ'}")
        if failed:
            return 2
        return 0 if not differences else 1
    finally:
        if not args.keep:
            shutil.rmtree(root, ignore_errors=True)


if __name__ == "__main__":
    sys.exit(main())
