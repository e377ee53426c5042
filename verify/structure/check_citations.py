#!/usr/bin/env python3
"""Checks that what the sources and docs cite is in the repository.

check_citations.py SOURCE_DIR

A clone has docs/, not the specifications the project was built from, so nothing may send a
reader to a file the clone lacks. Over every text file of the tree (sources, scripts, CMake
files, case files, notebooks and the Markdown pages; build folders and hidden folders left out):

1. No name of a specification kept outside the repository: MODEL.md, VIBRATION.md, FAULTS.md,
   RECORDS.md, PLANETARY.md, HELICAL.md, STIFFNESS-MODELS.md, STEADY-STATE.md, the paper's text
   yang-lin-1987.txt, or a path into a folder beside the repository (../shared, /work/shared).
2. Every path that starts at one of the repository's top folders (docs/..., lib/src/...,
   verify/..., paper_data/..., examples/..., ...) names a file or folder that exists, from the
   repository's root or from the citing file's folder. A capitalised placeholder in a file name
   (examples/NAME.py, paper_data/caseN.toml) stands for any name.
3. Every bare page name (faults.md, vibration.md#anchor) in a Markdown page, a comment or a
   string is a page of docs/, of the citing file's folder or of the root; REPORT.md, which
   `gearimpact reproduce` writes, fe_check.md, fe_crack.md, fe_spall.md and fe_chip.md, which
   `gearimpact fe-check` writes, and DATASET_CARD.md, which `gearimpact dataset merge` writes,
   are the outputs named so.
4. Every relative link of a Markdown page, [text](target), names a file that exists.

Prints each violation as FILE:LINE and exits 1 when there is one.
"""
import os
import re
import sys
from pathlib import Path

OUTSIDE = re.compile(
    r"(?<![\w-])"
    r"(MODEL|VIBRATION|FAULTS|RECORDS|PLANETARY|HELICAL|STIFFNESS-MODELS|STEADY-STATE)\.md\b"
    r"|yang-lin-1987\.txt|\.\./shared\b|/work/shared\b")
# The folders a repository path starts with (lib/ only with include/ or src/: lib/cmake and
# lib/pkgconfig are places under an install prefix).
TOP = (r"(?:docs|verify|reference|python|examples|paper_data|benchmarks|scripts|fuzz|cmake|\.ci"
       r"|lib/(?:include|src))")
PATH = re.compile(r"(?<![\w./$}-])((?:\.\./)*" + TOP + r"(?:/[\w.*-]+)+)")
PAGE = re.compile(r"(?<![\w./-])([\w-]+\.md)(?=[#)\s`'\",.:;]|$)")
LINK = re.compile(r"\]\(([^)\s#]+)(?:#[^)]*)?\)")
OUTPUTS = {"REPORT.md", "fe_check.md", "fe_crack.md", "fe_spall.md", "fe_chip.md",
           "DATASET_CARD.md"}
TEXT = {".md", ".cpp", ".hpp", ".h", ".py", ".sh", ".cmake", ".txt", ".toml", ".cfg", ".ipynb",
        ".in", ".yml", ".yaml", ".gp"}
PLACEHOLDER = re.compile(r"[A-Z]+")


def text_files(root: Path):
    for folder, dirs, files in os.walk(root):
        here = Path(folder)
        # Not hidden folders (.git; the CI's .ci stays), build folders (build*, a CMakeCache.txt),
        # Python's virtual environments and package metadata: what they hold is made, not cited.
        dirs[:] = sorted(d for d in dirs if (not d.startswith(".") or d == ".ci")
                         and not d.startswith("build") and not d.endswith(".egg-info")
                         and d != "__pycache__" and not (here / d / "CMakeCache.txt").exists()
                         and not (here / d / "pyvenv.cfg").exists())
        for name in sorted(files):
            path = here / name
            if path.suffix in TEXT or name in ("CMakeLists.txt", "run") or path.parent.name == ".ci":
                yield path


def exists(token: str, citing: Path, root: Path) -> bool:
    token = token.rstrip(".,:;")
    for base in (root, citing.parent):
        candidate = base / token
        if candidate.exists():
            return True
        # A capitalised placeholder in the file name stands for any name.
        if PLACEHOLDER.search(candidate.name) and candidate.parent.is_dir():
            pattern = re.compile(
                "^" + "".join(".+" if part.isupper() else re.escape(part)
                              for part in re.split(r"([A-Z]+)", candidate.name)) + "$")
            if any(pattern.match(p.name) for p in candidate.parent.iterdir()):
                return True
        if "*" in token and list(base.glob(token)):
            return True
        # A program or a fuzz target named after its source file.
        if any(candidate.with_name(candidate.name + ext).is_file() for ext in (".cpp", ".py", ".sh")):
            return True
    return False


def cited_text(path: Path, line: str) -> str:
    """The part of a line that cites: all of a page, a Python or CMake file; of C++, its comments
    and strings; of a shell script, its comments (its paths are in the folder it works in)."""
    if path.suffix == ".sh":
        comment = re.search(r"(?:^|\s)#.*", line)
        return comment.group(0) if comment else ""
    if path.suffix not in (".cpp", ".hpp", ".h"):
        return line
    comment = line.find("//")
    code, rest = (line, "") if comment < 0 else (line[:comment], line[comment:])
    strings = re.findall(r'"((?:[^"\\]|\\.)*)"', code)
    block = re.findall(r"/\*(.*?)(?:\*/|$)", code)
    lead = code.lstrip()
    if lead.startswith("*"):  # inside a block comment
        strings.append(lead)
    return " ".join(strings + block + [rest])


def check(root: Path) -> list:
    failures = []
    for path in text_files(root):
        try:
            text = path.read_text(encoding="utf-8")
        except UnicodeDecodeError:
            continue  # a fuzzing corpus's invalid UTF-8 on purpose
        if path.resolve() == Path(__file__).resolve():
            continue  # this script names what it forbids
        where = path.relative_to(root)
        for number, line in enumerate(text.splitlines(), 1):
            for match in OUTSIDE.finditer(line):
                failures.append(f"{where}:{number}: cites {match.group(0)}, which is not in the "
                                "repository (cite docs/)")
            for match in PATH.finditer(cited_text(path, line) if path.suffix == ".sh" else line):
                if not exists(match.group(1), path, root):
                    failures.append(f"{where}:{number}: cites {match.group(1)}, which does not exist")
            for match in PAGE.finditer(cited_text(path, line)):
                page = match.group(1)
                if OUTSIDE.fullmatch(page) or page in OUTPUTS:
                    continue
                if not any((base / page).is_file() for base in (root / "docs", path.parent, root)):
                    failures.append(f"{where}:{number}: cites the page {page}, which does not exist")
            if path.suffix == ".md":
                for match in LINK.finditer(line):
                    target = match.group(1)
                    if re.match(r"^[a-z]+:", target):
                        continue  # https:, mailto:
                    if not (path.parent / target).exists():
                        failures.append(f"{where}:{number}: links to {target}, which does not exist")
    return failures


def self_test() -> list:
    """The check finds each kind of bad citation in a small tree, and passes the good ones."""
    import tempfile
    with tempfile.TemporaryDirectory() as folder:
        root = Path(folder)
        (root / "docs").mkdir()
        (root / "lib" / "src").mkdir(parents=True)
        (root / "examples").mkdir()
        (root / "examples" / "rig.toml").write_text("")
        (root / "docs" / "model.md").write_text(
            "Good: [model](model.md#a), model.md, ../examples/rig.toml, examples/NAME.toml.\n"
            "Bad: [gone](gone.md), VIBRATION.md, ../shared/x, docs/gone.md\n")
        (root / "lib" / "src" / "a.cpp").write_text(
            "// Good: docs/model.md, model.md. Bad: FAULTS.md, faults.md, docs/gone.md\n"
            "double x = lines.md;\n")
        found = [f.split(": ", 1)[1] for f in check(root)]
        expected = ["links to gone.md, which does not exist",
                    "cites the page gone.md, which does not exist",
                    "cites VIBRATION.md, which is not in the repository (cite docs/)",
                    "cites ../shared, which is not in the repository (cite docs/)",
                    "cites docs/gone.md, which does not exist",
                    "cites FAULTS.md, which is not in the repository (cite docs/)",
                    "cites the page faults.md, which does not exist"]
        wrong = [f"self-test: expected '{e}'" for e in expected if found.count(e) < 1]
        wrong += [f"self-test: unexpected '{f}'" for f in found if f not in expected]
        # docs/gone.md is cited by both files.
        if found.count("cites docs/gone.md, which does not exist") != 2:
            wrong.append("self-test: docs/gone.md should be found twice")
        return wrong


def main() -> int:
    failures = self_test() + check(Path(sys.argv[1]).resolve())
    for failure in failures:
        print(failure)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
