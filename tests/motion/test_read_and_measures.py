"""GroundMotion: reading every real record, units, components, gaps, processing,
intensity measures against closed forms, response spectrum, bad input, large records."""

from __future__ import annotations

import io
import math
import time
import tracemalloc

import numpy as np
import pytest
from _records import BAD_RECORD_TYPES, BAD_RECORDS, PGV_TABLE_CM_S, RECORD_TABLE, at2_text, decimals, record_path

from isolator import errors
from isolator.errors import ComponentError, GapsError, MissingUnitsError, RecordOptionError
from isolator.motion import (
    GroundMotion,
    RecordError,
    intensity_measures,
    list_components,
    pseudo_acceleration_spectrum,
    read_ground_motion,
)
from isolator.units import STANDARD_GRAVITY

G = STANDARD_GRAVITY
READ_LIMIT_S = 120.0  # a hang guard, not a benchmark: timings are measured, not asserted (README)


# --------------------------------------------------------------------------------------
# Real records
# --------------------------------------------------------------------------------------


@pytest.mark.shared
@pytest.mark.parametrize("key", list(RECORD_TABLE))
def test_every_real_record_reads_with_readme_npts_dt_pga(records_dir, key):
    npts, dt_s, pga_g, options = RECORD_TABLE[key]
    motion = read_ground_motion(record_path(records_dir, key), **options)
    assert motion.npts == npts
    assert motion.dt_s == pytest.approx(dt_s, rel=1e-9)
    assert motion.acceleration_m_s2.dtype == np.float64
    assert motion.trace.stats.units == "m/s2"
    assert round(motion.pga_m_s2 / G, decimals(pga_g)) == float(pga_g)
    assert motion.units_source
    assert motion.provenance["path"].endswith(key.split("#")[0].split("/")[-1])
    assert motion.duration_s == pytest.approx((npts - 1) * dt_s)
    assert motion.time_s[-1] == pytest.approx(motion.duration_s)


@pytest.mark.shared
@pytest.mark.parametrize("key", list(PGV_TABLE_CM_S))
def test_pgv_matches_readme_table(records_dir, key):
    """Unfiltered PGV is the raw trapezoidal integral: equal to the README's to its 0.1 cm/s."""
    motion = read_ground_motion(record_path(records_dir, key), **RECORD_TABLE[key][3])
    pgv_cm_s = motion.intensity_measures().pgv_m_s * 100
    assert abs(pgv_cm_s - PGV_TABLE_CM_S[key]) <= 0.05 + 1e-9


@pytest.mark.shared
@pytest.mark.parametrize("name", ["RSN1044_NORTHR_NWH360", "RSN779_LOMAP_LGP000"])
def test_converted_mseed_and_sac_equal_the_at2(records_dir, name):
    at2 = read_ground_motion(records_dir / f"at2/{name}.AT2")
    mseed = read_ground_motion(records_dir / f"converted/converted_{name}.mseed", units="m/s2")
    sac = read_ground_motion(records_dir / f"converted/converted_{name}.sac")
    np.testing.assert_array_equal(mseed.acceleration_m_s2, at2.acceleration_m_s2)  # float64 exactly
    assert np.max(np.abs(sac.acceleration_m_s2 - at2.acceleration_m_s2)) <= 2.4e-7  # float32 in SAC
    assert mseed.units_source == "--units m/s2"
    assert sac.units_source == "SAC header kuser0 = 'm/s**2'"
    assert at2.units_source == "file header (AT2: g)"
    assert mseed.dt_s == sac.dt_s == at2.dt_s


@pytest.mark.shared
def test_units_sources_and_provenance(records_dir):
    knet = read_ground_motion(records_dir / "other/AOM0081801241951.NS")
    assert knet.units_source.startswith("K-NET scale factor")
    assert knet.processing[0]["step"] == "demean"  # NIED convention, recorded
    assert knet.provenance["station"] == "AOM008"
    at2 = read_ground_motion(records_dir / "at2/RSN1120_KOBE_TAK000.AT2")
    assert at2.provenance["event"] == "Kobe Japan" and at2.provenance["station"] == "Takatori"
    assert at2.processing == []
    text = read_ground_motion(records_dir / "other/elcentro.txt", units="g")
    assert text.units_source == "--units g"
    assert read_ground_motion(records_dir / "other/0111a.smc").units_source.startswith("file format (USGS SMC")


@pytest.mark.shared
def test_units_are_never_guessed(records_dir):
    for path in ("converted/converted_RSN779_LOMAP_LGP000.mseed", "other/elcentro.txt"):
        with pytest.raises(MissingUnitsError, match="does not state its units"):
            read_ground_motion(records_dir / path)
    with pytest.raises(RecordError, match="file states g"):
        read_ground_motion(records_dir / "at2/TAK000.AT2", units="cm/s2")
    assert read_ground_motion(records_dir / "at2/TAK000.AT2", units="g").npts == 4096  # agreeing is fine


@pytest.mark.shared
def test_components_listed_picked_and_ambiguity_refused(records_dir):
    path = records_dir / "other/ce89486SampleInput.v2"
    assert list_components(path) == ["HN1 (180)", "HN2 (90)", "HNZ (Up)"]
    with pytest.raises(ComponentError) as caught:
        read_ground_motion(path)
    assert "HN1 (180), HN2 (90), HNZ (Up)" in str(caught.value) and "--" not in str(caught.value)
    assert read_ground_motion(path, component="HN2").component == "HN2 (90)"
    assert read_ground_motion(path, component="z").component == "HNZ (Up)"
    assert read_ground_motion(path, component="180").components == ["HN1 (180)", "HN2 (90)", "HNZ (Up)"]
    assert read_ground_motion(path, component="E").component == "HN2 (90)"  # azimuth 90: E-W axis
    assert read_ground_motion(path, component="n").component == "HN1 (180)"  # azimuth 180: N-S axis
    with pytest.raises(RecordError, match=r"no component 'HNE' \(choices: HN1 \(180\)"):
        read_ground_motion(path, component="HNE")


def _three_component_mseed(path, channels=("HNE", "HNN", "HNZ"), dtype=np.float64):
    from obspy import Stream, Trace

    traces = [Trace(np.arange(100, dtype=dtype) * (i + 1), header={"delta": 0.01, "station": "STA",
                                                                   "network": "XX", "channel": channel})
              for i, channel in enumerate(channels)]
    Stream(traces).write(str(path), format="MSEED")


def test_component_by_channel_code_or_orientation_letter(tmp_path):
    path = tmp_path / "three.mseed"
    _three_component_mseed(path)
    assert list_components(path) == ["HNE", "HNN", "HNZ"]
    assert read_ground_motion(path, component="N", units="gal").acceleration_m_s2[1] == pytest.approx(0.02)
    assert read_ground_motion(path, component="XX.STA..HNZ", units="gal").component == "HNZ"
    ambiguous = tmp_path / "two_sensors.mseed"
    _three_component_mseed(ambiguous, channels=("HNE", "BNE"))
    with pytest.raises(RecordError, match="ambiguous: it matches HNE = XX.STA..HNE, BNE = XX.STA..BNE"):
        read_ground_motion(ambiguous, component="E", units="g")


def test_counts_need_a_response_or_factor(tmp_path):
    path = tmp_path / "counts.mseed"
    _three_component_mseed(path, channels=("HNZ",), dtype=np.int32)
    with pytest.raises(RecordError, match="integer counts"):
        read_ground_motion(path, units="g")
    with pytest.raises(RecordOptionError, match="without the units"):
        read_ground_motion(path, counts_factor=1e-3)
    motion = read_ground_motion(path, counts_factor=1e-3, units="gal")
    assert motion.acceleration_m_s2[10] == pytest.approx(10 * 1e-3 * 0.01)
    assert motion.units_source == "--counts-factor 0.001 gal per count"


def test_velocity_channel_refused_without_response(tmp_path):
    path = tmp_path / "bhz.mseed"
    _three_component_mseed(path, channels=("BHZ",))
    with pytest.raises(RecordError, match="seismometer"):
        read_ground_motion(path, units="m/s2")


def test_gaps_refused_or_merged(make_bad_record):
    path, options, _ = make_bad_record("gaps")
    with pytest.raises(GapsError, match="not merged"):
        read_ground_motion(path, **options)
    merged = read_ground_motion(path, merge=True, **options)
    assert merged.npts == 500 + 49 + 500
    assert merged.processing[0]["step"] == "merge"
    assert np.all(np.isfinite(merged.acceleration_m_s2))


def test_text_with_units_metadata_needs_no_option(tmp_path):
    path = tmp_path / "meta.dat"
    path.write_text("# units: gal\n# dt_s: 0.02\n1\n-2\n3\n")
    motion = read_ground_motion(path)
    np.testing.assert_allclose(motion.acceleration_m_s2, [0.01, -0.02, 0.03])
    assert motion.units_source == "file header ('# units: gal')"
    one_column = tmp_path / "meta_no_dt.dat"
    one_column.write_text("# units: g\n0.1\n0.2\n0.3\n")
    assert read_ground_motion(one_column, dt_s=0.005).dt_s == 0.005


# --------------------------------------------------------------------------------------
# Bad input: every case gives a RecordError, one line, naming the file
# --------------------------------------------------------------------------------------


@pytest.mark.parametrize("name", sorted(BAD_RECORDS))
def test_bad_input_gives_one_line_record_error(make_bad_record, name):
    path, options, words = make_bad_record(name)
    with pytest.raises(RecordError) as caught:
        read_ground_motion(path, **options)
    message = str(caught.value)
    assert isinstance(caught.value, ValueError)
    assert "\n" not in message
    assert message.startswith(str(path))
    for word in words:
        assert word in message, (word, message)
    # typed (callers catch by type) and never naming a command-line flag
    kind, _ = BAD_RECORD_TYPES.get(name, ("RecordError", ""))
    assert isinstance(caught.value, getattr(errors, kind)), (kind, type(caught.value))
    assert " --" not in message and not message.startswith("--"), message


# --------------------------------------------------------------------------------------
# Intensity measures against closed forms
# --------------------------------------------------------------------------------------


def _harmonic(amplitude_m: float, omega_rad_s: float, periods: int = 10, per_period: int = 4000):
    """Ground displacement A0(1 − cos Ωt): acceleration A0Ω² cos Ωt, velocity A0Ω sin Ωt from rest."""
    dt_s = 2 * math.pi / omega_rad_s / per_period
    time_s = np.arange(periods * per_period + 1) * dt_s
    return amplitude_m * omega_rad_s**2 * np.cos(omega_rad_s * time_s), dt_s


def test_harmonic_equivalent_amplitude_and_frequency_are_exact_for_a_sine():
    amplitude_m, omega_rad_s = 0.08, 2 * math.pi * 0.7
    acceleration, dt_s = _harmonic(amplitude_m, omega_rad_s)
    measures = intensity_measures(acceleration, dt_s)
    assert measures.pga_m_s2 == pytest.approx(amplitude_m * omega_rad_s**2, rel=1e-12)
    assert measures.a0_equiv_m == pytest.approx(amplitude_m, rel=1e-6)
    assert measures.omega_equiv_rad_s == pytest.approx(omega_rad_s, rel=1e-6)
    assert measures.pgd_m == pytest.approx(amplitude_m, rel=2e-2)  # the baseline fit removes the 1 − cos offset
    assert measures.predominant_period_s == pytest.approx(2 * math.pi / omega_rad_s, rel=0.05)


def test_arias_intensity_of_a_sine():
    amplitude_m_s2, omega_rad_s, periods = 3.0, 2 * math.pi * 2.0, 20
    dt_s = 2 * math.pi / omega_rad_s / 100
    time_s = np.arange(periods * 100 + 1) * dt_s
    acceleration = amplitude_m_s2 * np.sin(omega_rad_s * time_s)
    duration_s = time_s[-1]
    expected_m_s = math.pi / (2 * G) * amplitude_m_s2**2 * duration_s / 2  # π/(2g)·∫a², ∫sin² = T/2
    assert intensity_measures(acceleration, dt_s).arias_m_s == pytest.approx(expected_m_s, rel=1e-10)


def test_significant_duration_of_a_constant_is_90_percent():
    measures = intensity_measures(np.full(1001, 0.5), 0.01)
    assert measures.d5_95_s == pytest.approx(0.9 * 10.0, rel=1e-12)


def _resonant_response_peak(amplitude, omega, zeta, end_s):
    """Closed form: u'' + 2ζωu' + ω²u = −A sin ωt from rest; max |u| on a fine grid."""
    time_s = np.linspace(0.0, end_s, 400001)
    omega_d = omega * math.sqrt(1 - zeta**2)
    c1 = -amplitude / (2 * zeta * omega**2)
    c2 = zeta * omega * c1 / omega_d
    u = amplitude / (2 * zeta * omega**2) * np.cos(omega * time_s) + np.exp(-zeta * omega * time_s) * (
        c1 * np.cos(omega_d * time_s) + c2 * np.sin(omega_d * time_s))
    return np.max(np.abs(u))


@pytest.mark.parametrize("periods", [3, 40])
def test_response_spectrum_at_resonance_matches_closed_form(periods):
    amplitude_m_s2, period_s, zeta = 2.0, 0.5, 0.05
    omega = 2 * math.pi / period_s
    dt_s = period_s / 200
    time_s = np.arange(periods * 200 + 1) * dt_s
    acceleration = amplitude_m_s2 * np.sin(omega * time_s)
    psa = pseudo_acceleration_spectrum(acceleration, dt_s, [period_s], damping_ratio=zeta)[0]
    expected = omega**2 * _resonant_response_peak(amplitude_m_s2, omega, zeta, time_s[-1])
    assert psa == pytest.approx(expected, rel=5e-4)
    if periods == 40:  # steady state: A / (2ζ)
        assert psa == pytest.approx(amplitude_m_s2 / (2 * zeta), rel=1e-3)


def test_response_spectrum_is_exact_for_piecewise_linear_input():
    """A linear rise then a constant: exact, peak between samples included (coarse dt = T/10)."""
    period_s, zeta, dt_s, rise_s = 1.0, 0.0, 0.1, 0.1
    omega = 2 * math.pi / period_s
    acceleration = np.ones(101)
    acceleration[0] = 0.0  # rises linearly from 0 to 1 over the first step
    time_s = np.linspace(0.0, 10.0, 400001)

    def ramp(t):  # undamped response to a(t) = t / rise from rest
        t = np.maximum(t, 0)
        return -(t / rise_s - np.sin(omega * t) / (omega * rise_s)) / omega**2

    expected = omega**2 * np.max(np.abs(ramp(time_s) - ramp(time_s - rise_s)))
    psa = pseudo_acceleration_spectrum(acceleration, dt_s, [period_s], damping_ratio=zeta)[0]
    assert psa == pytest.approx(expected, rel=1e-8)


@pytest.mark.shared
def test_response_spectrum_against_scipy_first_order_hold(records_dir):
    """Independent reference: scipy's exact FOH discretisation (cont2discrete + lfilter), peaks
    at the samples only; the solver also finds the peaks between samples, so it is ≥ and close."""
    from scipy.signal import cont2discrete, lfilter, ss2tf

    motion = read_ground_motion(records_dir / "at2/RSN1044_NORTHR_NWH360.AT2")
    periods_s = np.array([0.1, 0.3, 1.0, 3.0])
    spectrum = motion.response_spectrum(periods_s)
    for period_s, psa in zip(periods_s, spectrum, strict=True):
        omega = 2 * math.pi / period_s
        system = (np.array([[0.0, 1.0], [-omega**2, -2 * 0.05 * omega]]), np.array([[0.0], [-1.0]]),
                  np.array([[1.0, 0.0]]), np.zeros((1, 1)))
        numerator, denominator = ss2tf(*cont2discrete(system, motion.dt_s, method="foh")[:4])
        reference = omega**2 * np.max(np.abs(lfilter(numerator[0], denominator, motion.acceleration_m_s2)))
        # a sampled oscillation misses its crest by at most the factor cos(ω dt / 2)
        assert reference * (1 - 1e-9) <= psa <= reference / math.cos(omega * motion.dt_s / 2) * 1.001


# --------------------------------------------------------------------------------------
# Processing
# --------------------------------------------------------------------------------------


@pytest.fixture
def synthetic():
    time_s = np.arange(2000) * 0.01
    acceleration = 0.3 + 2.0 * np.sin(2 * math.pi * 1.5 * time_s) + 0.05 * time_s
    return GroundMotion.from_array(acceleration, 0.01, component="X")


def test_processing_returns_new_motions_and_records_steps(synthetic):
    original = synthetic.acceleration_m_s2.copy()
    processed = (synthetic.demeaned().baseline_corrected(1).tapered(0.05)
                 .bandpassed(0.1, 20.0).resampled(0.005, method="lanczos").trimmed(1.0, 15.0))
    np.testing.assert_array_equal(synthetic.acceleration_m_s2, original)
    assert [step["step"] for step in processed.processing] == [
        "demean", "baseline", "taper", "bandpass", "resample", "trim"]
    assert processed.dt_s == pytest.approx(0.005)
    assert processed.duration_s == pytest.approx(14.0, abs=0.006)
    assert processed.acceleration_m_s2.dtype == np.float64
    assert processed.units_source == synthetic.units_source and processed.component == "X"


def test_demean_and_baseline(synthetic):
    assert abs(np.mean(synthetic.demeaned().acceleration_m_s2)) < 1e-12
    line = GroundMotion.from_array(1.0 + 0.2 * np.arange(100), 0.1)
    assert np.max(np.abs(line.baseline_corrected(1).acceleration_m_s2)) < 1e-10


def test_scaling(synthetic):
    assert synthetic.scaled(2.0).pga_m_s2 == pytest.approx(2 * synthetic.pga_m_s2)
    scaled = synthetic.scaled_to_pga(0.3 * G)
    assert scaled.pga_m_s2 == pytest.approx(0.3 * G, rel=1e-12)
    assert scaled.processing[-1]["target_pga_m_s2"] == pytest.approx(0.3 * G)


def test_fft_resample_and_invalid_processing(synthetic):
    assert synthetic.resampled(0.02).npts == 1000
    with pytest.raises(ValueError, match="Nyquist"):
        synthetic.bandpassed(1.0, 60.0)
    with pytest.raises(ValueError, match="fewer than"):
        synthetic.trimmed(5.0, 5.0)
    with pytest.raises(ValueError):
        GroundMotion.from_array([1.0], 0.01)
    with pytest.raises(ValueError):
        GroundMotion.from_array([1.0, np.nan], 0.01)


# --------------------------------------------------------------------------------------
# Large records: seconds, bounded memory
# --------------------------------------------------------------------------------------


#: Samples formatted once and repeated to fill the two-million-sample files: formatting every sample took ~2 s of CPU
#: per file, more than the AT2's read.  The reader parses the same bytes either way (same lines, widths, count);
#: what the tests check (the count, the time, the memory) does not depend on the values.
BLOCK_SAMPLES = 20_000


def _savetxt(rows, fmt: str) -> str:
    out = io.StringIO()
    np.savetxt(out, rows, fmt=fmt, delimiter="")
    return out.getvalue()


def _repeated_text(npts: int, format_block, separator: str) -> str:
    """The text of ``npts`` samples of 0.1 sin(0.01 n): the first :data:`BLOCK_SAMPLES` formatted by ``format_block``
    and repeated, joined by ``separator``."""
    assert npts % BLOCK_SAMPLES == 0
    block = format_block(0.1 * np.sin(np.arange(BLOCK_SAMPLES) * 0.01))
    return separator.join([block] * (npts // BLOCK_SAMPLES))


@pytest.mark.slow
def test_two_million_sample_at2_reads_fast_in_bounded_memory(tmp_path):
    npts = 2_000_000
    path = tmp_path / "big.AT2"
    with open(path, "w") as handle:
        handle.write(at2_text([], npts=npts, dt=".0050"))
        handle.write(_repeated_text(npts, lambda block: _savetxt(block.reshape(-1, 5), "%15.7E"), ""))
    tracemalloc.start()
    start = time.perf_counter()
    motion = read_ground_motion(path)
    elapsed_s = time.perf_counter() - start
    _, peak_bytes = tracemalloc.get_traced_memory()
    tracemalloc.stop()
    assert motion.npts == npts
    assert elapsed_s < READ_LIMIT_S
    assert peak_bytes < 20 * npts * 8  # the 16 MB result plus bounded chunks and copies


@pytest.mark.slow
def test_two_million_sample_text_reads_fast(tmp_path):
    npts = 2_000_000
    path = tmp_path / "big.acc"
    path.write_text(_repeated_text(npts, lambda block: "\n".join(f"{v:.6e}" for v in block), "\n"))
    start = time.perf_counter()
    motion = read_ground_motion(path, units="g", dt_s=0.01)
    assert time.perf_counter() - start < READ_LIMIT_S
    assert motion.npts == npts


def test_counts_with_stationxml_response(tmp_path):
    from obspy import Trace, UTCDateTime
    from obspy.core.inventory import Channel, Inventory, Network, Response, Station

    start = UTCDateTime(2020, 1, 1)
    response = Response.from_paz(zeros=[], poles=[], stage_gain=1e6, stage_gain_frequency=1.0,
                                 input_units="M/S**2", output_units="COUNTS")  # flat: 1e6 counts per m/s²
    channel = Channel(code="HNZ", location_code="", latitude=0, longitude=0, elevation=0, depth=0,
                      sample_rate=100, response=response, start_date=start - 86400)
    station = Station(code="STA", latitude=0, longitude=0, elevation=0, channels=[channel], start_date=start - 86400)
    inventory_path = tmp_path / "station.xml"
    Inventory(networks=[Network(code="XX", stations=[station])], source="test").write(
        str(inventory_path), format="STATIONXML")
    acceleration = 0.5 * np.sin(2 * np.pi * 2 * np.arange(2000) * 0.01)
    record = tmp_path / "counts.mseed"
    Trace((acceleration * 1e6).astype(np.int32), header={"network": "XX", "station": "STA", "channel": "HNZ",
                                                        "delta": 0.01, "starttime": start}).write(str(record))
    motion = read_ground_motion(record, response=inventory_path)
    assert motion.units_source == "instrument response (station.xml, output ACC)"
    assert motion.processing[0]["step"] == "remove_response"
    middle = slice(200, 1800)  # obspy tapers the ends before deconvolving
    np.testing.assert_allclose(motion.acceleration_m_s2[middle], acceleration[middle], atol=1e-5)
    with pytest.raises(RecordError, match="not both"):
        read_ground_motion(record, response=inventory_path, units="g")
    with pytest.raises(RecordError, match="cannot remove the instrument response"):
        read_ground_motion(record, response=tmp_path / "missing.xml")


_FUZZ_ALPHABET = "0123456789.-+eE ,;\t\n\r#NaNinfDTPS=abc*"


@pytest.mark.parametrize(("base", "suffix"), [
    (at2_text([0.01 * i for i in range(23)]), ".AT2"),
    ("# t, a\n0,0.1\n0.01,0.2\n0.02,0.3\n0.03,0.1\n", ".csv"),
])
def test_damaged_files_never_escape_as_other_exceptions(tmp_path, base, suffix):
    """Random edits of a valid file: either a GroundMotion or a one-line RecordError, nothing else."""
    from hypothesis import HealthCheck, given, settings
    from hypothesis import strategies as st

    edits = st.lists(st.tuples(st.integers(0, len(base) - 1), st.sampled_from(["set", "insert", "delete"]),
                               st.sampled_from(_FUZZ_ALPHABET)), min_size=1, max_size=6)

    @settings(max_examples=40, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])
    @given(edits=edits, cut=st.one_of(st.none(), st.integers(0, len(base))))
    def check(edits, cut):
        text = list(base)
        for position, action, character in edits:
            position = min(position, max(len(text) - 1, 0))
            if action == "set" and text:
                text[position] = character
            elif action == "insert":
                text.insert(position, character)
            elif text:
                del text[position]
        path = tmp_path / f"fuzz{suffix}"
        path.write_text("".join(text if cut is None else text[:cut]), newline="")
        for options in ({}, {"units": "g"}):
            try:
                read_ground_motion(path, **options)
            except RecordError as err:
                assert "\n" not in str(err)

    check()
