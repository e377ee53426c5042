"""GearimpactWarning and what a case's user should hear about before trusting a
run of it: the fillet-foundation fit used outside its range, mean torques that
do not balance and initial speeds that do not roll. The numbers and the
verdicts are the library's (_core.case_conditions); this module words them."""

import os
import sys
import warnings

from . import _core

_PACKAGE_DIR = os.path.dirname(os.path.abspath(__file__))


class GearimpactWarning(UserWarning):
    """A case or result that runs but may not be what was meant: the
    fillet-foundation fit extrapolated, unbalanced mean torques, initial speeds
    that do not roll (Rb1 w1 != Rb2 w2), a plain number for a length taken in
    metres though it is implausible as one. ``warnings.simplefilter("error",
    gearimpact.GearimpactWarning)`` turns them into errors."""


def warn(message):
    """Warns with the line of the caller's code outside this package, so that the
    message points at the user's call however deep in the package it arose."""
    frame = sys._getframe(1)
    level = 2
    while frame is not None and os.path.dirname(
            os.path.abspath(frame.f_code.co_filename)) == _PACKAGE_DIR:
        frame = frame.f_back
        level += 1
    warnings.warn(message, GearimpactWarning, stacklevel=level)


def _g(value):
    return f"{value:.6g}"


def extrapolation_text(case_name, warning):
    """The library's warning of the foundation fit (naming the gear, the
    parameter, its value and the fit's range), for the case named."""
    return f"{case_name}: {warning}"


def conditions(case):
    """{condition: message} of the conditions that hold for the case:
    "extrapolated", "unbalanced", "not_rolling"."""
    c = _core.case_conditions(case)
    name = case.name or "the case"
    found = {}
    if c["foundation_extrapolated"]:
        found["extrapolated"] = extrapolation_text(name, c["foundation_warning"])
    if c["balanced"] is False:
        t1, t2, balancing = c["mean_torque1_n_m"], c["mean_torque2_n_m"], c["balancing_torque2_n_m"]
        key = "torque2_value" if case.fields()["torque2.kind"] == "constant" else "torque2_mean"
        imbalance = t1 / c["rb1_m"] + t2 / c["rb2_m"]
        consequence = (
            "without friction the pair would accelerate without bound; with it a steady speed "
            "needs the excess power T1 w1 + T2 w2 to equal friction's mean power, which this "
            "check does not compute" if c["friction"] else
            "the pair accelerates without bound and has no steady state")
        found["unbalanced"] = (
            f"{name}: mean torques unbalanced, T1 = {_g(t1)} N*m, T2 = {_g(t2)} N*m "
            f"(T1/Rb1 + T2/Rb2 = {_g(imbalance)} N): {consequence}; "
            f"{key}={balancing!r} (N*m) balances T1"
            f"{' without friction' if c['friction'] else ''}")
    if not c["rolling"]:
        w1, w2, rolling = c["w1_rad_s"], c["w2_rad_s"], c["rolling_w2_rad_s"]
        found["not_rolling"] = (
            f"{name}: initial speeds do not roll, Rb1 w1 = {_g(c['rb1_m'] * w1)} m/s, "
            f"Rb2 w2 = {_g(c['rb2_m'] * w2)} m/s (w1 = {_g(w1)} rad/s, w2 = {_g(w2)} rad/s): "
            f"the teeth start with a relative speed and the pair settles at another speed; "
            f'w2="{rolling!r} rad/s" rolls with w1')
    return found


def warn_conditions(case, before=None):
    """Warns of each condition of the case, those of `before` (a case it was made
    from) excepted: a change warns of what it brings, not of what was there."""
    known = conditions(before) if before is not None else {}
    for condition, message in conditions(case).items():
        if condition not in known:
            warn(message)
