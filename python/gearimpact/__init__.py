"""Spur gear impact dynamics after Yang and Lin (1987), from Python.

The C++ library gearimpact with numpy arrays in and out. Every function gives
the same numbers as the program of the same name (``gearimpact stiffness``,
``simulate``, ``energy-ratios``, ``sweep-friction``), bit for bit.

Cases
    ``case(name="my-pair", teeth1=23, module="3 mm", ...)`` (keys alone, the
    schema's defaults for the rest), ``paper_case(n)`` (Table 1),
    ``read_case(path)`` (a case file, TOML), ``parse_case(text)``;
    ``case.replace(module="2.5 mm", friction_coefficient=0.06)`` changes fields
    with the units of case files (or SI floats). A key is its bare name where
    one section has it (``bore_diameter1``), else ``section_key``
    (``torque1_value``).
Results
    ``stiffness``, ``energy_ratios`` (dicts of numpy arrays), ``simulate``
    (a ``SimulationResult`` with ``.summary`` and ``.series``),
    ``sweep_friction`` (Fig. 7), ``reproduce`` (every figure and REPORT.md),
    ``modes`` (the natural modes of the linearised planar model).
Tables
    dicts of numpy arrays: text columns as str arrays, ``converged`` as bool,
    keys and counts (``line``, ``index``, ``period``, ``pairs``) as int64, the
    rest float64 (NaN where the program leaves a field empty).
Errors and warnings
    ``CaseError`` (a ``ValueError``) for any bad input, naming the key or
    argument as written; ``ConvergenceError`` (``RuntimeError``; its subclass
    ``QuadratureError``) for a computation that did not converge, and
    ``SimulationError`` (``RuntimeError``) for a run that cannot continue.
    ``GearimpactWarning`` (a ``UserWarning``) for a fillet-foundation fit used
    outside its range, unbalanced mean torques, initial speeds that do not
    roll and a plain number implausible as a length in metres. Ctrl-C stops a
    long computation (``KeyboardInterrupt``).

Units are SI inside (m, kg, s, N, rad); unit strings are converted once, where
they are read.
"""

from ._core import (
    CaseError,
    ConvergenceError,
    QuadratureError,
    SimulationError,
    Case,
    GearPair,
    StiffnessModel,
    __version__,
    base_pitch,
    base_radius,
    contact_angle,
    contact_ratio,
    contact_segment,
    line_of_action_length,
    moment_of_inertia,
    pitch_point_position,
    pitch_radius,
    tip_radius,
)
from ._cases import case, gear_pair, paper_case, parse_case, read_case
from ._warnings import GearimpactWarning
from ._results import (
    SimulationResult,
    energy_ratios,
    planetary_modes,
    train_modes,
    simulate,
    stiffness,
    sweep_friction,
    train,
)
from ._dataset import dataset_merge, dataset_plan, dataset_run, load_dataset
from ._signals import decimate, indicators, low_pass, order_analysis, spectrum, tacho_angle, tacho_jitter
from ._program import (
    iso6336,
    mesh_stiffness,
    modes,
    paper_data_dir,
    program_path,
    reproduce,
    ste,
    sweep,
)

__all__ = [
    "Case",
    "CaseError",
    "ConvergenceError",
    "GearPair",
    "GearimpactWarning",
    "QuadratureError",
    "SimulationError",
    "SimulationResult",
    "StiffnessModel",
    "base_pitch",
    "base_radius",
    "case",
    "contact_angle",
    "contact_ratio",
    "contact_segment",
    "dataset_merge",
    "dataset_plan",
    "dataset_run",
    "decimate",
    "energy_ratios",
    "gear_pair",
    "indicators",
    "iso6336",
    "line_of_action_length",
    "low_pass",
    "load_dataset",
    "mesh_stiffness",
    "modes",
    "moment_of_inertia",
    "order_analysis",
    "tacho_angle",
    "tacho_jitter",
    "paper_case",
    "paper_data_dir",
    "parse_case",
    "pitch_point_position",
    "pitch_radius",
    "planetary_modes",
    "train_modes",
    "program_path",
    "read_case",
    "reproduce",
    "simulate",
    "spectrum",
    "ste",
    "stiffness",
    "sweep",
    "sweep_friction",
    "tip_radius",
    "train",
]
