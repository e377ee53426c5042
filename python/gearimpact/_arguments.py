"""The checks of the functions' own arguments (not a case's keys, which the
case-file reader checks): each refuses a value with one CaseError naming the
argument as the caller wrote it and what it takes, before any work starts.
The ranges are the library's; these check what Python would otherwise let
through silently: a bool taken for a number or a number for a bool, NaN and
infinity, an integer that is no double, a str taken for a list."""

import math
import numbers
import os

import numpy

from ._core import CaseError

# Doubles hold every integer up to 2**53 exactly; beyond it an integer would
# silently become a neighbouring one (10**300 does not even fit the int64 of
# a case file's integer).
EXACT_INTEGER = 2**53


def case_error(message, field="", file=""):
    """A CaseError with its .field and .file, raised from Python."""
    error = CaseError(message)
    error.field = field
    error.file = file
    return error


def is_bool(value):
    return isinstance(value, (bool, numpy.bool_))


def exact_integer(name, value):
    """`value`, an integer, unless it is beyond what a double holds exactly."""
    if abs(int(value)) > EXACT_INTEGER:
        digits = len(str(abs(int(value))))
        shown = repr(value) if digits <= 30 else f"<an integer of {digits} digits>"
        raise case_error(
            f"{name}={shown}: an integer of at most 2**53 = {EXACT_INTEGER} in magnitude "
            f"(beyond it a double does not hold every integer); give a float or a unit string "
            f"for a larger value",
            name,
        )
    return int(value)


def real(name, value):
    """A finite real number (an int, float or numpy number, not a bool), as a float."""
    if is_bool(value) or not isinstance(value, numbers.Real):
        raise case_error(f"{name}={value!r}: a finite number, not {type(value).__name__}", name)
    if isinstance(value, numbers.Integral):
        return float(exact_integer(name, value))
    number = float(value)
    if not math.isfinite(number):
        raise case_error(f"{name}={value!r}: a finite number", name)
    return number


def integer(name, value):
    """An integer (int or numpy integer, not a bool) within 2**53; its range is the library's."""
    if is_bool(value) or not isinstance(value, numbers.Integral):
        raise case_error(f"{name}={value!r}: an integer, not {type(value).__name__}", name)
    return exact_integer(name, value)


def flag(name, value):
    """True or False (a numpy bool too), nothing else."""
    if not is_bool(value):
        raise case_error(f"{name}={value!r}: True or False, not {type(value).__name__}", name)
    return bool(value)


def text(name, value, what="a str"):
    """A str that UTF-8 can hold (no lone surrogates, which a file cannot hold either)."""
    if not isinstance(value, str):
        raise case_error(f"{name}={value!r}: {what}, not {type(value).__name__}", name)
    try:
        value.encode("utf-8")
    except UnicodeEncodeError as error:
        raise case_error(
            f"{name}: character {error.start + 1} is a lone surrogate, which UTF-8 (and a case "
            "file) cannot hold",
            name,
        ) from None
    return value


def path(name, value):
    """A path: a str or an os.PathLike of a str."""
    if isinstance(value, os.PathLike):
        value = os.fspath(value)
    return text(name, value, "a path (a str or a pathlib.Path)")


def quantity(name, value):
    """A number in SI or a unit string as a case file writes it ("500 rad/s"), as text."""
    if isinstance(value, str):
        return value
    if is_bool(value) or not isinstance(value, numbers.Real):
        raise case_error(
            f"{name}={value!r}: a number in SI units or a unit string (\"500 rad/s\"), "
            f"not {type(value).__name__}",
            name,
        )
    return repr(real(name, value))


def strings(name, value, example):
    """A list or tuple of str; a str alone is refused (iterating it would give its characters)."""
    if isinstance(value, str):
        raise case_error(
            f"{name}={value!r}: a list of str, one a word, as {name}={value.split()!r}", name
        )
    if not isinstance(value, (list, tuple)):
        raise case_error(
            f"{name}={value!r}: a list of str, e.g. {name}={example!r}, not {type(value).__name__}",
            name,
        )
    for i, item in enumerate(value):
        text(f"{name}[{i}]", item)
    return list(value)
