"""`isolator info`: JSON keys and values, the readable table, one-line errors with exit code 2."""

from __future__ import annotations

import json

import pytest
from _records import BAD_RECORD_TYPES, BAD_RECORDS, RECORD_TABLE, decimals, record_path
from typer.testing import CliRunner

from isolator.cli import app, load_record_for_cli

RUNNER = CliRunner()
JSON_KEYS = {"npts", "dt_s", "duration_s", "units_source", "pga_m_s2", "pgv_m_s", "pgd_m", "arias_m_s",
             "d5_95_s", "a0_equiv_m", "omega_equiv_rad_s", "components"}


def _cli_options(options: dict) -> list[str]:
    arguments = []
    for key, value in options.items():
        arguments += {"units": ["--units", str(value)], "dt_s": ["--dt", str(value)],
                      "component": ["--component", str(value)]}[key]
    return arguments


@pytest.mark.shared
@pytest.mark.parametrize("key", list(RECORD_TABLE))
def test_info_json_on_every_real_record(records_dir, key):
    npts, dt_s, pga_g, options = RECORD_TABLE[key]
    result = RUNNER.invoke(app, ["info", str(record_path(records_dir, key)), "--json", *_cli_options(options)])
    assert result.exit_code == 0, result.stderr
    summary = json.loads(result.stdout)
    assert JSON_KEYS <= set(summary)
    assert summary["npts"] == npts
    assert summary["dt_s"] == pytest.approx(dt_s)
    assert round(summary["pga_m_s2"] / 9.80665, decimals(pga_g)) == float(pga_g)
    assert summary["a0_equiv_m"] == pytest.approx(summary["pgv_m_s"] ** 2 / summary["pga_m_s2"])
    assert isinstance(summary["components"], list) and summary["components"]
    assert "NaN" not in result.stdout and "Infinity" not in result.stdout


@pytest.mark.shared
def test_info_table_is_readable(records_dir):
    result = RUNNER.invoke(app, ["info", str(records_dir / "at2/RSN1044_NORTHR_NWH360.AT2")])
    assert result.exit_code == 0
    assert "PGA" in result.stdout and "m/s²" in result.stdout and "(0.5904 g)" in result.stdout
    assert "file header (AT2: g)" in result.stdout


@pytest.mark.shared
def test_info_multi_component_needs_component(records_dir):
    path = str(records_dir / "other/ce89486SampleInput.v2")
    result = RUNNER.invoke(app, ["info", path])
    assert result.exit_code == 2
    assert "HN1 (180), HN2 (90), HNZ (Up)" in result.stderr
    assert RUNNER.invoke(app, ["info", path, "-c", "90", "--json"]).exit_code == 0


def test_info_refuses_a_record_of_zeros_instead_of_nan_measures(tmp_path):
    # a record of zeros has no A0 = PGV²/PGA (0/0): the record is at fault, said in one line
    path = tmp_path / "zeros.txt"
    path.write_text("0 0\n0.01 0\n0.02 0\n")
    result = RUNNER.invoke(app, ["info", str(path), "--units", "g", "--json"])
    assert result.exit_code == 2 and result.stdout == ""
    assert result.stderr == f"error: {path}: every one of its 3 samples is zero: no ground motion\n"


@pytest.mark.parametrize("name", sorted(BAD_RECORDS))
def test_info_bad_input_exit_2_one_line(make_bad_record, name):
    path, options, words = make_bad_record(name)
    result = RUNNER.invoke(app, ["info", str(path), *_cli_options(options)])
    assert result.exit_code == 2, (result.stdout, result.stderr)
    lines = result.stderr.strip().splitlines()
    assert len(lines) == 1, result.stderr
    assert str(path) in lines[0]
    assert "Traceback" not in result.stderr + result.stdout
    for word in words:
        assert word in lines[0]
    flag = BAD_RECORD_TYPES.get(name, ("", ""))[1]
    assert flag in lines[0], (flag, lines[0])  # the CLI names the option that fixes it


def test_merge_option_joins_gaps(make_bad_record):
    path, options, _ = make_bad_record("gaps")
    result = RUNNER.invoke(app, ["info", str(path), "--units", "m/s2", "--merge", "--json"])
    assert result.exit_code == 0
    assert json.loads(result.stdout)["processing"][0]["step"] == "merge"


def test_load_record_for_cli_exits_2(tmp_path):
    import typer

    with pytest.raises(typer.Exit) as caught:
        load_record_for_cli(tmp_path / "nothing.AT2")
    assert caught.value.exit_code == 2
