"""`isolator report`: the PDF opens, has its four pages, and its text matches the JSON."""

from __future__ import annotations

import json
import math
from pathlib import Path

import pytest
from typer.testing import CliRunner

from isolator.cli import app

pypdf = pytest.importorskip("pypdf")
runner = CliRunner()
DATA = Path(__file__).resolve().parents[2] / "data"

REQUIRED_KEYS = ("regime_record", "regime_harmonic", "amplified_record", "amplified_harmonic",
                 "dominant_force_record", "dominant_force_harmonic", "k", "alpha", "eta",
                 "peak_displacement_m", "peak_transmitted_acceleration_m_s2")


@pytest.fixture(autouse=True)
def _cache(tmp_path, monkeypatch):
    monkeypatch.setenv("ISOLATOR_CACHE_DIR", str(tmp_path / "cache"))


@pytest.fixture(scope="module")
def knet_report(tmp_path_factory):
    """One report on obspy's bundled K-NET record (5900 samples), scaled to 0.3 g, coarse map."""
    out = tmp_path_factory.mktemp("report") / "knet.pdf"
    with pytest.MonkeyPatch.context() as patch:
        patch.setenv("ISOLATOR_CACHE_DIR", str(out.parent / "cache"))
        result = runner.invoke(app, ["report", "--design", str(DATA / "example_pendulum.toml"), "example:knet",
                                     "--scale-to-pga", "0.3", "-o", str(out), "--map-resolution", "10"])
    return result, out


def _text(page) -> str:
    return " ".join(page.extract_text().split())


def test_report_pages_and_json(knet_report):
    result, out = knet_report
    assert result.exit_code == 0, result.output
    reader = pypdf.PdfReader(str(out))
    assert len(reader.pages) == 4
    titles = ["Summary", "Ground motion", "Isolator response", "Harmonic regime map"]
    texts = [_text(page) for page in reader.pages]
    for number, (title, text) in enumerate(zip(titles, texts, strict=True), start=1):
        assert f"{number} {title}" in text
    summary = json.loads(out.with_suffix(".json").read_text())
    for key in REQUIRED_KEYS:
        assert key in summary
    page1 = texts[0]
    for key in ("k", "alpha", "peak_displacement_m", "peak_transmitted_acceleration_m_s2"):
        assert format(summary[key], ".4g") in page1, key
    assert summary["regime_record"] in page1 and summary["regime_harmonic"] in page1
    assert summary["dominant_force_record"] in page1
    assert "scaled to the design PGA 0.3 g" in page1
    assert "AKT013" in page1 and "isolator 0.1.0" in page1
    assert summary["record"]["intensity_measures"]["pga_m_s2"] == pytest.approx(0.3 * 9.80665)
    assert format(summary["record"]["intensity_measures"]["pga_m_s2"], ".4g") in page1
    for text in texts[1:]:
        assert "[s]" in text or "[-]" in text  # units on the axes
    assert "isolated period T" in texts[1]
    assert "Force-displacement loop" in texts[2] and "Energy balance over time" in texts[2]
    assert "A(α)" in texts[3] or "A( α)" in texts[3] or "amplitude" in texts[3].lower()
    assert math.isfinite(summary["amplitude_record"]) and summary["map"]["resolution"] == 10
    assert not list(out.parent.glob(".*.tmp"))  # atomic writes leave nothing behind


def test_report_output_summary_lines(knet_report):
    result, _ = knet_report
    assert "regime" in result.output and "peak displacement" in result.output


@pytest.mark.parametrize("args,words", [
    (["--design", "absent.toml", "example:knet"], "no such design file"),
    (["--design", str(DATA / "example_pendulum.toml"), "example:nothing"], "unknown example record"),
    (["--design", str(DATA / "example_pendulum.toml"), "example:knet", "--scale-to-pga", "-1"], "--scale-to-pga must lie in [1e-06, 50] g, got -1"),
    (["--design", str(DATA / "example_pendulum.toml"), "no_such_record.AT2"], "no such file"),
    (["--design", str(DATA / "example_pendulum.toml"), "example:knet", "-o", "x.txt"], "must end with .pdf"),
])
def test_report_user_errors(args, words):
    result = runner.invoke(app, ["report", *args])
    assert result.exit_code == 2
    assert words in result.output
    assert "Traceback" not in result.output


def test_bad_design_key_is_one_line(tmp_path):
    design = tmp_path / "d.toml"
    design.write_text('name = "x"\nmass_kg = 1000\nradius = 2.0\nmu_static = 0.05\n')
    result = runner.invoke(app, ["report", "--design", str(design), "example:knet"])
    assert result.exit_code == 2
    assert "unknown key 'radius' (did you mean 'radius_m'?)" in result.output
    assert len(result.output.strip().splitlines()) == 1


def test_regime_map_command(tmp_path):
    out = tmp_path / "map.png"
    result = runner.invoke(app, ["regime-map", "--frame", "fig6", "-n", "8", "-o", str(out)])
    assert result.exit_code == 0, result.output
    assert out.is_file() and "triple point" in result.output and "η = 0.5" in result.output
    again = runner.invoke(app, ["regime-map", "--frame", "fig6", "-n", "8"])
    assert "read from cache" in again.output
    bad = runner.invoke(app, ["regime-map", "--frame", "fig9"])
    assert bad.exit_code == 2 and "unknown --frame" in bad.output


def test_report_on_a_shared_record(records_dir, tmp_path):
    out = tmp_path / "elcentro.pdf"
    result = runner.invoke(app, ["report", "--design", str(DATA / "example_pendulum_damped.toml"),
                                 str(records_dir / "at2" / "elCentro.AT2"), "-o", str(out), "--map-resolution", "8"])
    assert result.exit_code == 0, result.output
    summary = json.loads(out.with_suffix(".json").read_text())
    assert summary["eta"] > 0 and summary["record"]["component"]
    assert len(pypdf.PdfReader(str(out)).pages) == 4


SHARED_CASES = [
    ("at2/RSN1044_NORTHR_NWH360.AT2", {}),
    ("other/elcentro.txt", {"units": "g"}),
    ("other/IELC180.acc", {"units": "g", "dt_s": 0.01}),
    ("other/Chi-Chi_1999_TCU068-090.csv", {"units": "g"}),
    ("other/ce89486SampleInput.v2", {"component": "180"}),
    ("other/0111a.smc", {}),
    ("other/AOM0081801241951.NS", {}),
    ("converted/converted_RSN779_LOMAP_LGP000.mseed", {"units": "m/s2"}),
]


@pytest.mark.parametrize("name,options", SHARED_CASES)
def test_every_format_analyses_to_json(records_dir, name, options):
    """The analysis behind the report (no PDF) on one record of each format of ../shared/records."""
    from isolator.design import Design
    from isolator.motion import read_ground_motion
    from isolator.report.summary import analyse, summary_dict

    motion = read_ground_motion(records_dir / name, **options)
    analysis = analyse(Design.from_toml(DATA / "example_pendulum.toml"), motion, record_label=name)
    summary = json.loads(json.dumps(summary_dict(analysis), allow_nan=False))
    for key in REQUIRED_KEYS:
        assert summary[key] is not None
    assert summary["regime_record"] in ("ST", "SS", "SL")
    assert abs(summary["energy_balance_error_J_per_kg"]) < 1e-6 * max(1.0, summary["energy_input_J_per_kg"])
    if summary["regime_record"] == "ST":
        assert summary["peak_displacement_m"] == 0.0


def test_report_prints_its_parameters_and_set_changes_a_check(tmp_path, knet_report):
    """Page 1 and the JSON list the review parameters of the checks at their defaults; ``--set D_over_R_max=0.01``
    moves the D/R row's limit (the same peak displacement), marks the parameter as set, and the rows agree."""
    result, with_pdf = knet_report
    beside = json.loads(with_pdf.with_suffix(".json").read_text())
    assert [row["name"] for row in beside["parameters"]][-1] == "drift_limit_rha"
    assert all("source" not in row for row in beside["parameters"])
    page1 = _text(pypdf.PdfReader(str(with_pdf)).pages[0])
    assert "Parameters of the checks" in page1 and "D_over_R_max = 0.25 [practice]" in page1
    out = tmp_path / "knet.pdf"
    result = runner.invoke(app, ["report", "--design", str(DATA / "example_pendulum.toml"), "example:knet",
                                 "--scale-to-pga", "0.3", "-o", str(out), "--map-resolution", "10", "--no-pdf",
                                 "--set", "D_over_R_max=0.01"])
    assert result.exit_code == 0, result.output
    alone = json.loads(out.with_suffix(".json").read_text())
    before = next(row for row in beside["checks"] if row["id"] == "D_over_R")
    after = next(row for row in alone["checks"] if row["id"] == "D_over_R")
    assert before["limit"] == 0.25 and after["limit"] == 0.01 and after["value"] == before["value"]
    assert after["status"] == ("pass" if after["value"] <= 0.01 else "fail")
    assert next(row for row in alone["parameters"] if row["name"] == "D_over_R_max")["source"] == "set"


def test_report_json_without_pdf(tmp_path, knet_report):
    """--no-pdf writes the same numbers as the report's JSON and renders nothing."""
    _, with_pdf = knet_report
    out = tmp_path / "knet.pdf"
    result = runner.invoke(app, ["report", "--design", str(DATA / "example_pendulum.toml"), "example:knet",
                                 "--scale-to-pga", "0.3", "-o", str(out), "--map-resolution", "10", "--no-pdf"])
    assert result.exit_code == 0, result.output
    assert not out.exists() and out.with_suffix(".json").is_file()
    alone = json.loads(out.with_suffix(".json").read_text())
    beside = json.loads(with_pdf.with_suffix(".json").read_text())
    assert "pdf" not in alone and beside["pdf"] == str(with_pdf)
    assert alone["schema_version"] == beside["schema_version"] == 2
    for key in ("alpha", "k", "peak_displacement_m", "energy_input_J_per_kg", "regime_record", "regime_harmonic"):
        assert alone[key] == beside[key], key
    assert alone["map"]["regime_at_design"] == beside["map"]["regime_at_design"]
