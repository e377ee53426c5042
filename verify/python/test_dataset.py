"""The Python twin of `gearimpact dataset` (docs/datasets.md): the same files as the program, bit
for bit, the set loaded back, and refusals naming the key or argument."""

import filecmp
import json
import pytest

import gearimpact


def _six(source_dir, tmp_path):
    """The six-record spec, its base case named by an absolute path, in tmp_path."""
    text = (source_dir / "verify" / "dataset" / "six.toml").read_text()
    text = text.replace('"../../examples/', f'"{source_dir / "examples"}/')
    (tmp_path / "six.toml").write_text(text)
    return tmp_path / "six.toml"


def test_run_and_merge_give_the_programs_files(cli, source_dir, tmp_path):
    spec = _six(source_dir, tmp_path)
    plan = gearimpact.dataset_plan(spec)
    assert plan["records"] == 6 and plan["samples_per_record"] == 1000
    made = gearimpact.dataset_run(spec, tmp_path / "py", shard=(0, 1))
    assert made["made"] == 6 and made["found_complete"] == 0
    again = gearimpact.dataset_run(spec, tmp_path / "py", shard=(0, 1))
    assert again["made"] == 0 and again["found_complete"] == 6
    gearimpact.dataset_merge(tmp_path / "py", tmp_path / "py-merged")
    program = json.loads(cli("dataset", spec, "--out", tmp_path / "cli", "--quiet"))
    cli("dataset", "merge", tmp_path / "cli", "--out", tmp_path / "cli-merged")
    names = sorted(p.name for p in (tmp_path / "cli-merged").iterdir())
    if program["code_version"] == plan["code_version"]:
        # One build: the same bytes in every file.
        _, mismatch, errors = filecmp.cmpfiles(tmp_path / "cli-merged", tmp_path / "py-merged",
                                               names, shallow=False)
        assert mismatch == [] and errors == []
    else:
        # Another build (an installed package beside the build tree's program): the records
        # carry their code version, so their bytes and digests differ; the labels do not.
        def labels(folder):
            rows = (folder / "labels.csv").read_text().splitlines()
            return [row.rsplit(",", 1)[0] for row in rows]

        assert labels(tmp_path / "cli-merged") == labels(tmp_path / "py-merged")
    pytest.importorskip("h5py")
    data = gearimpact.load_dataset(tmp_path / "py-merged")
    assert data["signals/sensor"].shape == (6, 1000)
    assert list(data["labels"]["faults[0].depth_m"]) == [2e-4, 6e-4, 1e-3] * 2
    assert list(data["labels"]["split"]) == ["train"] * 3 + ["test"] * 3
    if program["code_version"] != plan["code_version"]:
        cli_data = gearimpact.load_dataset(tmp_path / "cli-merged")
        assert (cli_data["signals/sensor"] == data["signals/sensor"]).all()


def test_refusals_name_the_key_and_the_argument(source_dir, tmp_path):
    spec = _six(source_dir, tmp_path)
    text = spec.read_text().replace('"faults[0].depth"', '"faults[0].dept"')
    (tmp_path / "bad.toml").write_text(text)
    with pytest.raises(gearimpact.CaseError) as error:
        gearimpact.dataset_plan(tmp_path / "bad.toml")
    assert "factors[1].key = faults[0].dept" in str(error.value)
    with pytest.raises(gearimpact.CaseError) as error:
        gearimpact.dataset_plan(spec, max_records=5)
    assert "records = 6" in str(error.value) and "max_records" in str(error.value)
    with pytest.raises(gearimpact.CaseError) as error:
        gearimpact.dataset_run(spec, tmp_path / "x", shard=(2, 2))
    assert error.value.field == "shard"
    assert not (tmp_path / "x").exists()
