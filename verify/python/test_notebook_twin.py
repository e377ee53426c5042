"""Each example notebook examples/NAME.ipynb is what examples/make_notebook.py writes
from its twin examples/NAME.py: the two say the same, cell by cell."""

import importlib.util

import nbformat


def test_every_notebook_is_written_from_its_twin(source_dir):
    examples = source_dir / "examples"
    spec = importlib.util.spec_from_file_location("make_notebook", examples / "make_notebook.py")
    make_notebook = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(make_notebook)
    assert sorted(make_notebook.NOTEBOOKS) == sorted(p.stem for p in examples.glob("*.ipynb"))
    for name in make_notebook.NOTEBOOKS:
        expected = make_notebook.notebook_of((examples / f"{name}.py").read_text())
        committed = nbformat.read(str(examples / f"{name}.ipynb"), as_version=4)
        assert [(c.cell_type, c.source) for c in committed.cells] == \
            [(c.cell_type, c.source) for c in expected.cells], \
            f"run /usr/bin/python3 examples/make_notebook.py after editing examples/{name}.py"
        assert all(not c.get("outputs") for c in committed.cells if c.cell_type == "code"), \
            f"commit {name}.ipynb without outputs"
