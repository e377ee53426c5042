"""Cases: Table 1's, case files, and changes from keyword arguments.

A change is made through the case-file reader itself: the case is written as
a case file in SI units, the changed keys are put into that text, and the text
is read back. So a keyword argument takes exactly what a case file takes (the
same keys, the same unit strings, the same ranges and messages), and an SI
float is written in the key's SI unit. The case file writes every key, and
its text reads back to the same case bit for bit, so the keys left alone do
not change.
"""

import json
import numbers
import re

try:
    import tomllib
except ImportError:  # Python < 3.11
    import tomli as tomllib

import numpy

from . import _arguments, _core
from ._arguments import case_error, is_bool
from ._core import Case, CaseError

# The pseudo file name of text built from keyword arguments; stripped from
# the reader's messages, which then name the keyword instead.
_KEYWORDS = "<keyword arguments>"

# The keys of a torque section depend on its kind: a new kind starts the
# section anew from the keys given with it.
_KIND_SECTIONS = ("torque1", "torque2")


def paper_case(number, torque_unit="kgf-mm", case3_frequency_rad_s=10000.0, **fields):
    """Case `number` (1, 2 or 3) of the paper's Table 1 on the gear pair of section 7.

    torque_unit: "kgf-mm" (docs/model.md's reading, the only one that reproduces
    Fig. 7) or "n-mm" (as the table is labelled). case3_frequency_rad_s: W of
    case 3's T1 = 200 sin(W t), a finite number in rad/s within
    torque1.angular_frequency's range; 1000 is the alternative reading.
    number: an int. Any other
    keyword changes a field of the case as in Case.replace, e.g.
    paper_case(2, damping_form="hunt-crossley", end_time="10 ms").
    """
    case = _core.paper_case(
        _arguments.integer("number", number),
        _arguments.text("torque_unit", torque_unit),
        _arguments.real("case3_frequency_rad_s", case3_frequency_rad_s),
    )
    return replace(case, **fields) if fields else case


def read_case(path):
    """Reads and checks a case file (TOML, docs/case-files.md); path: a str or a pathlib.Path.
    Raises CaseError."""
    return _core.read_case_file(_arguments.path("path", path))


def parse_case(text, name="<text>"):
    """Reads a case file's text (a str); `name` (a str) names it in messages (and the case,
    without a `name` key). Raises CaseError."""
    return _core.parse_case(_arguments.text("text", text), _arguments.text("name", name))


def gear_pair(**fields):
    """A GearPair from the keys of a case file's [gears], the paper's pair for the rest.

    gear_pair(teeth1=25, module="3 mm", youngs_modulus="210 GPa") or SI floats
    (module=0.003). Checked as a case file's pair is: a value outside its range
    raises CaseError naming the key.
    """
    paper = _core.paper_case(1, "kgf-mm", 10000.0)
    keys = sorted(key for key in fields_of(paper) if key.startswith("gears."))
    dotted = {}
    for key, value in fields.items():
        full = key if "." in key else "gears." + key
        if full not in keys:
            raise case_error(
                f"{key}: no such key of [gears]; the keys are "
                + ", ".join(k.partition(".")[2] for k in keys),
                key,
            )
        dotted[full] = value
    return replace(paper, **dotted).gears


def fields_of(case):
    """The case's fields as a case file has them in SI units: {"gears.module": "0.002 m", ...}."""
    document = tomllib.loads(case.to_toml("si"))
    flat = {}
    for key, value in document.items():
        if isinstance(value, dict):
            flat.update({f"{key}.{inner}": item for inner, item in value.items()})
        else:
            flat[key] = value
    return flat


def replace(case, **changes):
    """A copy of the case with fields changed; the case itself does not change.

    Keys are those of case files: "section.key" (as **{"torque1.value":
    "50 kgf*mm"}), section_key (torque1_value="50 kgf*mm",
    integrator_kind="adaptive") or the bare key where only one section has it
    (module, teeth1, friction_coefficient, step, end_time, w1, ...).
    Values are what a case file takes: unit strings ("2 mm", "0.1 us"),
    numbers, option names ("adaptive"); a number for a quantity is taken in SI
    units (module=0.002). Numbers are finite; integers at most 2**53 in
    magnitude. True/False stand for "on"/"off". A list key (the harmonic
    torque's amplitudes, angular_frequencies, phases) takes a non-empty list,
    tuple or 1-dimensional numpy array of numbers (SI) or unit strings:
    torque1_amplitudes=["10 N*m", 2.0]. Setting a torque's
    kind starts that torque anew from the keys given with it:
    replace(torque1_kind="sinusoidal", torque1_amplitude="200 kgf*mm",
    torque1_angular_frequency="1000 rad/s"). Raises CaseError naming the key
    as given.
    """
    if not changes:
        return case
    current = fields_of(case)
    given = {}
    for user_key, value in changes.items():
        given[_resolve(user_key, current)] = (user_key, value)
    literals = {key: _literal_of(value) for key, value in current.items()}
    for section in _KIND_SECTIONS:
        if section + ".kind" in given:
            literals = {k: v for k, v in literals.items() if not k.startswith(section + ".")}
    for dotted, (user_key, value) in given.items():
        literals[dotted] = _literal(user_key, dotted, value, current.get(dotted),
                                    _core.key_form(dotted))
    try:
        return _core.parse_case(_toml_text(literals), _KEYWORDS)
    except CaseError as error:
        raise _explained(error, given) from None


def _resolve(user_key, current):
    """The case file's section.key for a key as given: section.key itself,
    section_key (a keyword argument cannot hold a dot), or a bare key that
    only one section has."""
    if not isinstance(user_key, str) or not user_key:
        raise case_error(f"{user_key!r}: a key of a case file, as section.key or a bare key")
    known = _known_keys(current)
    if "." in user_key or user_key == "name":
        return _known(user_key, user_key, known)
    sections = {key.partition(".")[0] for key in known if "." in key}
    section, _, inner = user_key.partition("_")
    if section in sections and inner:
        return _known(f"{section}.{inner}", user_key, known)
    candidates = sorted(key for key in known if key.split(".")[-1] == user_key)
    if not candidates:
        # A key the writer leaves out at its default (friction_law,
        # mesh_damping_ratio, ...) is absent from the case's fields.
        candidates = sorted(
            f"{name}.{user_key}"
            for name in sections
            if _core.key_form(f"{name}.{user_key}") is not None
        )
    if len(candidates) == 1:
        return candidates[0]
    if candidates:
        raise case_error(
            f"{user_key}: more than one section has this key; write one of "
            + ", ".join(f"{key} ({key.replace('.', '_')})" for key in candidates),
            user_key,
        )
    raise case_error(
        f"{user_key}: no such key in a case file; the keys are "
        + ", ".join(sorted(known)),
        user_key,
    )


def _known_keys(current):
    return set(current) | set(_torque_template())


def _known(dotted, user_key, known):
    """`dotted` when the schema has it; the text built from the keys then
    holds only keys of the schema."""
    if dotted in known or _core.key_form(dotted) is not None:
        return dotted
    raise case_error(
        f"{user_key}: no such key in a case file; the keys are " + ", ".join(sorted(known)),
        user_key,
    )


_TEMPLATE = {}


def _torque_template():
    """The keys of a torque section of either kind, with their SI values, from
    Table 1's case 3 (a sinusoidal and a constant torque)."""
    if not _TEMPLATE:
        case3 = fields_of(_core.paper_case(3, "kgf-mm", 10000.0))
        for key, value in case3.items():
            section, _, inner = key.partition(".")
            if section in _KIND_SECTIONS:
                for name in _KIND_SECTIONS:
                    _TEMPLATE.setdefault(f"{name}.{inner}", value)
    return _TEMPLATE


def _literal_of(value):
    """The TOML text of a value read from a case file."""
    if isinstance(value, str):
        return json.dumps(value, ensure_ascii=False)
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, int):
        return str(value)
    if isinstance(value, list):
        return _toml_array([_literal_of(item) for item in value])
    return repr(float(value))


def _toml_array(items):
    """A TOML array over lines of 8 values, as the case-file writer writes
    one: the reader refuses lines over 4096 bytes."""
    lines = [", ".join(items[i:i + 8]) for i in range(0, len(items), 8)]
    return "[\n  " + ",\n  ".join(lines) + "\n]" if len(items) > 8 else "[" + ", ".join(items) + "]"


def _literal(user_key, dotted, value, current, form):
    """The TOML text of a value given for a key (whose present value is `current`;
    `form` is the key's (kind, SI unit) from the schema, None for an unknown key)."""
    kind, unit = form if form is not None else (None, None)
    if kind == "list":
        return _list_literal(user_key, dotted, value, unit)
    if is_bool(value):
        if current in ("on", "off"):
            return '"on"' if value else '"off"'
        return "true" if value else "false"
    if isinstance(value, numbers.Real):
        number = _arguments.real(user_key, value)
        if unit is not None:
            return json.dumps(f"{_core.shortest_decimal(number)} {unit}")
        if isinstance(value, numbers.Integral):
            return str(int(value))
        return repr(number)
    if isinstance(value, str):
        return json.dumps(value, ensure_ascii=False)
    raise case_error(
        f"{user_key}={value!r}: a number, a string (with its unit where the key has one) "
        f"or True/False, not {type(value).__name__}",
        user_key,
    )


def _list_literal(user_key, dotted, value, unit):
    """The TOML array of a list key: each element a unit string as given, or a
    number in SI written in the key's SI unit."""
    if isinstance(value, numpy.ndarray):
        if value.ndim != 1:
            raise case_error(
                f"{user_key}: a 1-dimensional list of numbers or unit strings, "
                f"not an array of shape {value.shape}",
                user_key,
            )
        value = value.tolist()
    if not isinstance(value, (list, tuple)):
        raise case_error(
            f"{user_key}={value!r}: a list of numbers (SI) or unit strings, e.g. "
            f"[\"10 N*m\", \"2 N*m\"], not {type(value).__name__}",
            user_key,
        )
    if not value:
        raise case_error(f"{user_key}=[]: a list of at least one number or unit string", user_key)
    most = _core.most_values(dotted)
    if len(value) > most:
        raise case_error(f"{user_key}: {len(value)} values; a list of at most {most} values",
                         user_key)
    items = []
    for i, item in enumerate(value):
        name = f"{user_key}[{i}]"
        if isinstance(item, str):
            items.append(json.dumps(item, ensure_ascii=False))
        elif not is_bool(item) and isinstance(item, numbers.Real):
            number = _arguments.real(name, item)
            items.append(json.dumps(f"{_core.shortest_decimal(number)} {unit}"))
        else:
            raise case_error(
                f"{name}={item!r}: a number in SI ({unit}) or a unit string, "
                f"not {type(item).__name__}",
                name,
            )
    return _toml_array(items)


def _toml_text(literals):
    top = [f"{key} = {text}" for key, text in literals.items() if "." not in key]
    sections = {}
    for key, text in literals.items():
        if "." in key:
            section, _, inner = key.partition(".")
            sections.setdefault(section, []).append(f"{inner} = {text}")
    lines = top
    for section, entries in sections.items():
        lines += ["", f"[{section}]"] + entries
    return "\n".join(lines) + "\n"


def _explained(error, given):
    """The reader's CaseError, naming the keyword arguments instead of the text built from them."""
    # Every line: the reader reports each problem on its own line.
    message = re.sub(r"^" + re.escape(_KEYWORDS) + r"(:\d+)?: ", "", str(error), flags=re.M)
    field = getattr(error, "field", "")
    # An element of a list key: torque1.amplitudes[1].
    key, bracket, index = field.partition("[")
    if field in given:
        user_key, value = given[field]
        text = f"{user_key}={value!r}: {message}"
    elif bracket and key in given:
        user_key, _ = given[key]
        field = f"{user_key}[{index}"
        text = f"{field}: {message}"
    else:
        changes = ", ".join(f"{key}={value!r}" for key, value in given.values())
        text = f"with {changes}: {message}"
    return case_error(text, field)


def _case_repr(case):
    return f"<gearimpact.Case {case.name!r}: print(case.to_toml()) shows every field>"


def _case_eq(case, other):
    if not isinstance(other, Case):
        return NotImplemented
    return case.to_toml("si") == other.to_toml("si")


Case.replace = replace
Case.fields = fields_of
Case.__repr__ = _case_repr
Case.__eq__ = _case_eq
Case.__hash__ = None
