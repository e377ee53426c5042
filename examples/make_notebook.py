"""Writes each example notebook (examples/NAME.ipynb) from its twin examples/NAME.py.

The twin is a plain script in the "percent" format: `# %%` starts a code cell,
`# %% [markdown]` a Markdown cell whose lines are comments. Run after editing
the twin: /usr/bin/python3 examples/make_notebook.py (needs python3-nbformat).
Each notebook is listed in NOTEBOOKS.
"""

import sys
from pathlib import Path

import nbformat

HERE = Path(__file__).resolve().parent
NOTEBOOKS = ("gear_pair", "cracked_pinion_vibration", "rig_cracks_dataset")


def cells_of(script):
    """(kind, source) of each cell of a percent-format script."""
    cells = []
    for line in script.splitlines():
        if line.startswith("# %%"):
            cells.append(["markdown" if "[markdown]" in line else "code", []])
        elif cells:
            cells[-1][1].append(line)
    result = []
    for kind, lines in cells:
        if kind == "markdown":
            lines = [line[2:] if line.startswith("# ") else line.lstrip("#") for line in lines]
        result.append((kind, "\n".join(lines).strip("\n")))
    return result


def notebook_of(script):
    notebook = nbformat.v4.new_notebook()
    notebook.metadata["kernelspec"] = {
        "display_name": "Python 3 (ipykernel)", "language": "python", "name": "python3"}
    notebook.metadata["language_info"] = {"name": "python"}
    for index, (kind, source) in enumerate(cells_of(script)):
        cell = (nbformat.v4.new_markdown_cell if kind == "markdown" else nbformat.v4.new_code_cell)(
            source)
        cell["id"] = f"cell-{index}"
        notebook.cells.append(cell)
    return notebook


def main():
    for name in NOTEBOOKS:
        script = (HERE / f"{name}.py").read_text()
        target = HERE / f"{name}.ipynb"
        nbformat.write(notebook_of(script), str(target))
        print(f"wrote {target}", file=sys.stderr)


if __name__ == "__main__":
    main()
