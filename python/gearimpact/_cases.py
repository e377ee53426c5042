"""Cases: Table 1's, case files, and changes from keyword arguments.

A change is made through the case-file reader itself: the case is written as
a case file in SI units, the changed keys are put into that text, and the text
is read back. So a keyword argument takes exactly what a case file takes (the
same keys, the same unit strings, the same ranges and messages), and an SI
float is written in the key's SI unit. The case file writes every key, and
its text reads back to the same case bit for bit, so the keys left alone do
not change.
"""

import difflib
import json
import math
import numbers
import re

try:
    import tomllib
except ImportError:  # Python < 3.11
    import tomli as tomllib

import numpy

from . import _arguments, _core, _warnings
from ._arguments import case_error, is_bool
from ._core import Case, CaseError

# The pseudo file name of text built from keyword arguments; stripped from
# the reader's messages, which then name the keyword instead.
_KEYWORDS = "<keyword arguments>"

# The keys of a torque section depend on its kind: a new kind starts the
# section anew from the keys given with it.
_KIND_SECTIONS = ("torque1", "torque2")

# Plausible values, m, of the lengths that a plain number (taken in SI metres)
# most often gives in millimetres by mistake; outside them a plain number warns
# (GearimpactWarning). They are no ranges (the schema's rows hold those): a
# module of 3 m is a valid input, and more likely a slip for "3 mm".
_PLAUSIBLE_LENGTHS_M = {
    # From watch gears to mill drives.
    "gears.module": ("a module", 0.05e-3, 100e-3),
    "gears.face_width": ("a face width", 0.1e-3, 2.0),
    "gears.bore_diameter1": ("a bore diameter", 0.5e-3, 5.0),
    "gears.bore_diameter2": ("a bore diameter", 0.5e-3, 5.0),
    # B, half the total play; 0 is a pair without play.
    "gears.backlash": ("a backlash", 0.0, 5e-3),
}


def case(name=None, **keys):
    """A case from keyword arguments alone: gearimpact.case(name="my-pair",
    teeth1=23, teeth2=67, module="3 mm", ...).

    name: the case's name (letters, digits, '_', '-', '.'; it names output
    files). keys: the keys of case files, as Case.replace takes them (the bare
    key where one section has it, section_key otherwise, e.g. torque1_value);
    values with units ("3 mm", "1000 rpm") or plain numbers in SI. A key left
    out takes the schema's default (``gearimpact schema``, docs/case-files.md);
    the keys without one (the pair's teeth, module, pressure angle, face width,
    material and backlash; for a run also the torques and end_time) must be given,
    and are listed together when missing. The pair's keys alone make a gear pair
    alone (like a pair file), which stiffness, ste, iso6336, modes and
    mesh_stiffness take; a run on it (simulate, sweep, sweep_friction) raises
    CaseError naming the keys it lacks (Case.run_keys_absent). A torque's kind follows from its keys when left out
    (torque1_value: "constant"). faults: a list of dicts with the keys of a
    [[faults]] table, one per faulted tooth (docs/faults.md), e.g.
    faults=[dict(gear="pinion", tooth=0, kind="root-crack", depth="0.5 mm",
    angle="45 deg")] or dict(gear="pinion", tooth=0, kind="spall", depth="0.2 mm",
    width="4 mm", start_radius="20 mm", end_radius="21 mm") or dict(gear="wheel",
    tooth=3, kind="tip-chip", radius="81.5 mm", width="5 mm"); errors name
    faults[i].key. Raises CaseError naming the key as given, with
    a suggestion for a misspelt one; warns (GearimpactWarning) of a foundation
    fit used outside its range, unbalanced mean torques and speeds that do not
    roll.
    """
    if name is None:
        raise case_error(
            'name: a case needs a name (it names output files), e.g. case(name="my-pair", ...)',
            "name")
    given = {"name": ("name", _arguments.text("name", name))}
    faults_text = _faults_text(keys.pop("faults", None))
    for user_key, value in keys.items():
        _add_given(given, resolve(user_key), user_key, value)
    for section in _KIND_SECTIONS:
        kind = _implied_kind(section, given)
        if kind is not None:
            given[section + ".kind"] = (None, kind)
    missing = _missing_keys(given, pair_alone=all(_schema()[key]["pair"] for key in given))
    if missing:
        raise case_error(
            f"case {name!r}: keys without a default are missing: " + "; ".join(missing),
            missing[0].split(" ")[0])
    literals = {dotted: _literal(user_key or dotted, dotted, value)
                for dotted, (user_key, value) in given.items()}
    try:
        made = _core.parse_pair_or_run(_toml_text(literals) + faults_text, _KEYWORDS)
    except CaseError as error:
        raise _explained(error, given) from None
    _warnings.warn_conditions(made)
    return made


def _faults_text(faults):
    """[[faults]] tables for faults=[dict(gear="pinion", tooth=0, kind="root-crack", depth="0.5 mm",
    angle="45 deg"), ...]: the reader checks the keys and values, and names them faults[i].key."""
    if faults is None:
        return ""
    if isinstance(faults, (str, bytes, dict)) or not hasattr(faults, "__iter__"):
        raise case_error(
            f"faults={faults!r}: a list of dicts, one per faulted tooth, e.g. "
            'faults=[dict(gear="pinion", tooth=0, kind="missing")]', "faults")
    text = ""
    for i, fault in enumerate(faults):
        if not isinstance(fault, dict):
            raise case_error(f"faults[{i}]={fault!r}: a dict of the keys of [[faults]] "
                             "(gear, tooth, kind, depth, angle, ...)", f"faults[{i}]")
        text += "\n[[faults]]\n"
        for key, value in fault.items():
            if not isinstance(key, str) or not re.fullmatch(r"[A-Za-z0-9_]+", key):
                raise case_error(f"faults[{i}]: the key {key!r} is not a key of [[faults]]",
                                 f"faults[{i}]")
            if is_bool(value) or not isinstance(value, (str, numbers.Integral, numbers.Real)):
                raise case_error(f"faults[{i}].{key}={value!r}: a string (\"0.5 mm\") or a number",
                                 f"faults[{i}].{key}")
            literal = json.dumps(value) if isinstance(value, str) else (
                str(int(value)) if isinstance(value, numbers.Integral) else repr(float(value)))
            text += f"{key} = {literal}\n"
    return text


def _add_given(given, dotted, user_key, value):
    if dotted in given:
        raise case_error(
            f"{user_key}: given twice, as {given[dotted][0]} and {user_key} ({dotted})", user_key)
    given[dotted] = (user_key, value)


def _condition_holds(row, given):
    """Whether the row's condition (only_when) holds with the given values or,
    for a condition key not given, the schema's default."""
    if row["only_when"] is None:
        return True
    key, choices = row["only_when"]
    if key in given:
        value = given[key][1]
    else:
        default = _schema()[key]["default"]
        value = json.loads(default) if default.startswith('"') else default
    return isinstance(value, str) and value in choices


def _implied_kind(section, given):
    """The one kind of a torque under which every key given for it applies,
    when the kind itself is not given; else None."""
    if section + ".kind" in given:
        return None
    rows = [row for key, row in _schema().items()
            if key.startswith(section + ".") and key in given]
    if not rows:
        return None
    kinds = {choice for row in _schema().values()
             if row["section"] == section and row["only_when"] for choice in row["only_when"][1]}
    fitting = [kind for kind in sorted(kinds)
               if all(row["only_when"] is None or kind in row["only_when"][1] for row in rows)]
    return fitting[0] if len(fitting) == 1 else None


def _missing_keys(given, pair_alone):
    """The required keys that apply and are not given, each as
    "keyword (section.key, in its unit: what it takes)". pair_alone: only the pair's keys are
    given, and only the pair's are required (a run on the case names the rest)."""
    missing = []
    for key, row in _schema().items():
        if pair_alone and not row["pair"]:
            continue
        if row["required"] and key not in given and _condition_holds(row, given):
            unit = f', in {row["unit"]}' if row["unit"] else ""
            missing.append(f"{_spelling(key)} ({key}{unit}: {row['allowed']})")
    return missing


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
    """Reads and checks a case file (TOML, docs/case-files.md), or a pair file (only [gears],
    [model], [modifications], [bearings], [shafts] and [[faults]]: a gear pair alone, as case()
    makes from the pair's keys); path: a str or a pathlib.Path. Raises CaseError; warns
    (GearimpactWarning) as case() does."""
    made = _core.read_pair_or_run_file(_arguments.path("path", path))
    _warnings.warn_conditions(made)
    return made


def parse_case(text, name="<text>"):
    """Reads a case file's or a pair file's text (a str), as read_case reads the file; `name` (a
    str) names it in messages (and the case, without a `name` key). Raises CaseError; warns
    (GearimpactWarning) as case() does."""
    made = _core.parse_pair_or_run(_arguments.text("text", text), _arguments.text("name", name))
    _warnings.warn_conditions(made)
    return made


def gear_pair(**fields):
    """A GearPair from the keys of a case file's [gears], the paper's pair for the rest.

    gear_pair(teeth1=25, module="3 mm", youngs_modulus="210 GPa") or SI floats
    (module=0.003). Checked as a case file's pair is: a value outside its range
    raises CaseError naming the key.
    """
    paper = _core.paper_case(1, "kgf-mm", 10000.0)
    for key in fields:
        if not resolve(key).startswith("gears."):
            raise case_error(
                f"{key}: not a key of [gears]; the keys are "
                + ", ".join(row["bare"] for row in _schema().values() if row["section"] == "gears"),
                key,
            )
    return replace(paper, **fields).gears


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
    # The [[faults]] tables are kept as they are, or replaced by faults=[...].
    kept = current.pop("faults", None)
    faults_text = _faults_text(changes.pop("faults", kept))
    given = {}
    for user_key, value in changes.items():
        _add_given(given, resolve(user_key), user_key, value)
    literals = {key: _literal_of(value) for key, value in current.items()}
    for section in _KIND_SECTIONS:
        if section + ".kind" in given:
            literals = {k: v for k, v in literals.items() if not k.startswith(section + ".")}
    for dotted, (user_key, value) in given.items():
        literals[dotted] = _literal(user_key, dotted, value)
    try:
        changed = _core.parse_pair_or_run(_toml_text(literals) + faults_text, _KEYWORDS)
    except CaseError as error:
        raise _explained(error, given) from None
    _warnings.warn_conditions(changed, before=case)
    return changed


_SCHEMA = {}


def _schema():
    """The schema's rows by section.key, in case-file order."""
    if not _SCHEMA:
        _SCHEMA.update((row["key"], row) for row in _core.schema_rows())
    return _SCHEMA


_SPELLINGS = {}


def _spellings():
    """{spelling: section.key} of every way a keyword argument may name a key:
    section.key, section_key (a keyword argument cannot hold a dot), and the
    bare key where only one section has it."""
    if not _SPELLINGS:
        rows = _schema()
        sections = {}
        for key, row in rows.items():
            sections.setdefault(row["bare"], []).append(key)
        for key, row in rows.items():
            _SPELLINGS[key] = key
            if row["section"]:
                _SPELLINGS[f"{row['section']}_{row['bare']}"] = key
            if len(sections[row["bare"]]) == 1:
                _SPELLINGS[row["bare"]] = key
    return _SPELLINGS


def _spelling(key):
    """The shortest keyword argument that names section.key."""
    return min((s for s, k in _spellings().items() if k == key and "." not in s), key=len)


def resolve(user_key):
    """The case file's section.key for a key as given: section.key itself,
    section_key, or a bare key that only one section has."""
    if not isinstance(user_key, str) or not user_key:
        raise case_error(f"{user_key!r}: a key of a case file, as section.key or a bare key")
    spellings = _spellings()
    if user_key in spellings:
        return spellings[user_key]
    candidates = sorted(key for key, row in _schema().items() if row["bare"] == user_key)
    if candidates:
        raise case_error(
            f"{user_key}: more than one section has this key; write one of "
            + ", ".join(f"{key} ({key.replace('.', '_')})" for key in candidates),
            user_key,
        )
    close = difflib.get_close_matches(user_key, list(spellings), n=6, cutoff=0.6)
    suggested = list(dict.fromkeys(spellings[name] for name in close))[:3]
    if suggested:
        hint = "did you mean " + " or ".join(f"{_spelling(key)} ({key})" for key in suggested) + "?"
    else:
        hint = "the keys are " + ", ".join(_schema())
    raise case_error(f"{user_key}: no such key in a case file; {hint}", user_key)


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


def _literal(user_key, dotted, value):
    """The TOML text of a value given for a key (section.key `dotted`, a key of
    the schema): a number for a quantity is written in the key's SI unit."""
    row = _schema()[dotted]
    unit = row["si_unit"]
    if row["kind"] in ("quantity_list", "number_list"):
        return _list_literal(user_key, dotted, value, unit)
    if is_bool(value):
        if row["kind"] == "on_off":
            return '"on"' if value else '"off"'
        return "true" if value else "false"
    if isinstance(value, numbers.Real):
        number = _arguments.real(user_key, value)
        if unit is not None:
            check_plausible(user_key, dotted, number)
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


def is_speed(dotted):
    """Whether the key is a speed, whose plain numbers (rad/s) warn."""
    return _core.plain_speed_warning(dotted, "1", dotted) is not None


def check_plausible(user_key, dotted, metres):
    """Warns when a plain number for a length is implausible in metres, and of any plain number
    for a speed (read in rad/s, where a person may mean rpm)."""
    speed = _core.plain_speed_warning(dotted, _core.shortest_decimal(metres), user_key)
    if speed is not None:
        _warnings.warn(speed)
        return
    if dotted not in _PLAUSIBLE_LENGTHS_M:
        return
    what, low, high = _PLAUSIBLE_LENGTHS_M[dotted]
    if low <= metres <= high:
        return
    written = _core.shortest_decimal(metres)
    message = (f"{user_key} = {written} m: SI metres assumed for a plain number; {what} is "
               f"plausibly {low * 1e3:g} mm to {high * 1e3:g} mm")
    if metres > high:
        message += f'; did you mean "{written} mm"?'
    _warnings.warn(message)


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
            if unit is None:  # a list of plain numbers
                items.append(repr(float(number)))
            else:
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
        text = f"{user_key or field}={value!r}: {message}"
    elif bracket and key in given:
        user_key, _ = given[key]
        field = f"{user_key or key}[{index}"
        text = f"{field}: {message}"
    else:
        changes = ", ".join(f"{key}={value!r}" for key, value in given.values() if key)
        text = f"with {changes}: {message}"
    return case_error(text, field)


def _short(number):
    return f"{number:.6g}"


def _si(fields, key):
    """A quantity of the case's SI fields ("0.003 m") as a float; 0 for one left out."""
    return float(str(fields.get(key, "0")).split()[0])


def _torque_text(fields, section, symbol):
    kind = fields[section + ".kind"]
    mean = _si(fields, section + ".mean")
    if kind == "constant":
        return f"{symbol} = {_short(_si(fields, section + '.value'))} N*m"
    if kind == "sinusoidal":
        amplitude = _short(_si(fields, section + ".amplitude"))
        frequency = _short(_si(fields, section + ".angular_frequency"))
        return f"{symbol} = {_short(mean)} + {amplitude} sin({frequency} rad/s t) N*m"
    if kind == "prescribed-speed":
        orders = len(fields.get(section + ".orders", []))
        speed = _si(fields, section + ".mean_speed")
        return (f"{symbol}: a driver at {_short(speed)} rad/s ({_short(speed * 30 / math.pi)} rpm)"
                f" + {orders} orders")
    if kind == "speed-controlled":
        speed = _si(fields, section + ".mean_speed")
        return (f"{symbol}: a speed controller at {_short(speed)} rad/s "
                f"({_short(speed * 30 / math.pi)} rpm)")
    if kind == "induction-motor":
        return (f"{symbol}: an induction motor, breakdown "
                f"{_short(_si(fields, section + '.breakdown_torque'))} N*m")
    if kind == "profile":
        points = len(fields.get(section + ".profile_times", []))
        return f"{symbol}: a profile of {points} points"
    if kind == "drag":
        return (f"{symbol}: a drag of {_short(_si(fields, section + '.drag_constant'))} N*m"
                f" + {_short(_si(fields, section + '.drag_viscous'))} N*m*s/rad w2")
    harmonics = len(fields.get(section + ".amplitudes", []))
    return f"{symbol} = {_short(mean)} N*m + {harmonics} harmonics"


def _speed_text(fields, key, symbol):
    w = _si(fields, key)
    return f"{symbol} = {_short(w)} rad/s ({_short(w * 30 / math.pi)} rpm)"


def _case_repr(case):
    """The pair, the torques and the speeds, short; case.to_toml() shows every field."""
    f = fields_of(case)
    pair = (
        f"<gearimpact.Case {case.name!r}: {f['gears.teeth1']}/{f['gears.teeth2']} teeth, "
        f"module {_short(_si(f, 'gears.module') * 1e3)} mm, "
        f"face width {_short(_si(f, 'gears.face_width') * 1e3)} mm; ")
    if case.run_keys_absent:
        return pair + "a gear pair alone (a run needs " + ", ".join(case.run_keys_absent) + ")>"
    return (
        pair +
        f"{_torque_text(f, 'torque1', 'T1')}, {_torque_text(f, 'torque2', 'T2')}; "
        f"{_speed_text(f, 'initial.w1', 'w1')}, {_speed_text(f, 'initial.w2', 'w2')}>"
    )


def _case_eq(case, other):
    if not isinstance(other, Case):
        return NotImplemented
    return case.to_toml("si") == other.to_toml("si")


Case.replace = replace
Case.fields = fields_of
Case.__repr__ = _case_repr
Case.__eq__ = _case_eq
Case.__hash__ = None
