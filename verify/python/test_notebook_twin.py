"""examples/gear_pair.ipynb is what examples/make_notebook.py writes from its
twin examples/gear_pair.py: the two say the same, cell by cell."""

import importlib.util

import nbformat


def test_the_notebook_is_written_from_its_twin(source_dir):
    examples = source_dir / "examples"
    spec = importlib.util.spec_from_file_location("make_notebook", examples / "make_notebook.py")
    make_notebook = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(make_notebook)
    expected = make_notebook.notebook_of((examples / "gear_pair.py").read_text())
    committed = nbformat.read(str(examples / "gear_pair.ipynb"), as_version=4)
    assert [(c.cell_type, c.source) for c in committed.cells] == \
        [(c.cell_type, c.source) for c in expected.cells], \
        "run /usr/bin/python3 examples/make_notebook.py after editing examples/gear_pair.py"
    assert all(not c.get("outputs") for c in committed.cells if c.cell_type == "code"), \
        "commit the notebook without outputs"
