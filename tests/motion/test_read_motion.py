"""One way to read and scale: read_motion for a component and a pair; MotionPair.scaled_to_pga; the notes."""

from __future__ import annotations

import numpy as np
import pytest

from isolator import errors
from isolator.motion import GroundMotion, MotionPair, RecordOptions, read_motion

G = 9.80665  # standard gravity [m/s²], written out: the test does not take it from the code under test


def _text(path, values, *, dt_s=None, units=None):
    """A text record: two columns (time, value) when ``dt_s`` is given, else one column; a units header line."""
    lines = [f"# units: {units}"] if units else []
    if dt_s is None:
        lines += [f"{v:.6f}" for v in values]
    else:
        lines += [f"{i * dt_s:.4f} {v:.6f}" for i, v in enumerate(values)]
    path.write_text("\n".join(lines) + "\n")
    return path


@pytest.fixture
def files(tmp_path):
    t = np.arange(400) * 0.01
    a_x, a_y = 0.2 * np.sin(2 * np.pi * t), 0.1 * np.cos(3 * np.pi * t)
    return {"silent_x": _text(tmp_path / "x.txt", a_x, dt_s=0.01),  # states no units
            "silent_y": _text(tmp_path / "y.txt", a_y, dt_s=0.01),
            "gal_y": _text(tmp_path / "y_gal.txt", 100 * a_y, dt_s=0.01, units="gal"),  # the same motion in gal
            "no_dt_y": _text(tmp_path / "y.acc", a_y),  # one column: no time step
            "a_x": a_x, "a_y": a_y}


def test_a_component_and_a_pair_take_the_units_the_same_way(files):
    """defaults=True: the units given go only to the files that state none, for one file as for each file of a
    pair; defaults=False: they must agree with a file that states its own, for one file as for a pair."""
    lenient = RecordOptions(units="g", defaults=True)
    single = read_motion(files["silent_x"], lenient)
    stated = read_motion(files["gal_y"], lenient)
    pair = read_motion(files["silent_x"], RecordOptions(pair=str(files["gal_y"]), units="g", defaults=True))
    assert isinstance(single, GroundMotion) and isinstance(pair, MotionPair)
    assert single.units_source == pair.x.units_source == "--units g"
    assert "gal" in stated.units_source and pair.y.units_source == stated.units_source
    # the files hold 6 decimals: 5e-7 g in X, 5e-7 gal in Y
    np.testing.assert_allclose(pair.x.acceleration_m_s2, files["a_x"] * G, rtol=0, atol=5.1e-7 * G)
    np.testing.assert_allclose(pair.y.acceleration_m_s2, files["a_y"], rtol=0, atol=5.1e-9)
    strict = RecordOptions(units="g")
    with pytest.raises(errors.UnitsConflictError):
        read_motion(files["gal_y"], strict)
    with pytest.raises(errors.UnitsConflictError):
        read_motion(files["silent_x"], RecordOptions(pair=str(files["gal_y"]), units="g"))
    for options in (RecordOptions(), RecordOptions(pair=str(files["silent_y"]))):  # nothing given: refused
        with pytest.raises(errors.MissingUnitsError):
            read_motion(files["silent_x"], options)


def test_a_component_and_a_pair_take_the_time_step_the_same_way(files):
    """A one-column file takes the time step given; a file with a time column keeps its own under defaults."""
    lenient = RecordOptions(units="g", dt_s=0.01, defaults=True)
    alone = read_motion(files["no_dt_y"], lenient)
    pair = read_motion(files["silent_x"], RecordOptions(pair=str(files["no_dt_y"]), units="g", dt_s=0.01,
                                                        defaults=True))
    assert alone.dt_s == pair.y.dt_s == pair.x.dt_s == 0.01
    np.testing.assert_array_equal(alone.acceleration_m_s2, pair.y.acceleration_m_s2)
    other_step = RecordOptions(units="g", dt_s=0.02, defaults=True)  # not the file's 0.01 s: the file wins
    assert read_motion(files["silent_x"], other_step).dt_s == 0.01
    with pytest.raises(errors.TimeStepConflictError):  # strict: the same value disagrees with the file
        read_motion(files["silent_x"], RecordOptions(units="g", dt_s=0.02))
    with pytest.raises(errors.MissingTimeStepError):
        read_motion(files["silent_x"], RecordOptions(pair=str(files["no_dt_y"]), units="g", defaults=True))


def test_pair_scaled_to_pga_against_a_hand_computation():
    """Larger horizontal PGA 3 m/s² (Y) to 0.6 g: factor 0.6 × 9.80665 / 3 = 1.96133 on every component,
    the vertical (4 m/s², larger than the horizontals) included but not measured."""
    x = GroundMotion.from_array(np.array([0.0, 1.0, -2.0, 0.5]), 0.01)
    y = GroundMotion.from_array(np.array([0.0, 3.0, -1.0, 0.0]), 0.01)
    z = GroundMotion.from_array(np.array([0.5, -4.0, 1.0, 0.0]), 0.01)
    scaled = MotionPair(x, y, z).scaled_to_pga(0.6 * G)
    factor = 1.96133
    assert scaled.processing[-1] == {"step": "scale_to_pga", "factor": pytest.approx(factor, rel=1e-12),
                                     "target_pga_m_s2": pytest.approx(0.6 * G), "from_pga_m_s2": 3.0,
                                     "measured_on": "larger horizontal"}
    np.testing.assert_allclose(scaled.x.acceleration_m_s2, [0.0, factor, -2 * factor, 0.5 * factor], rtol=1e-12)
    np.testing.assert_allclose(scaled.y.acceleration_m_s2, [0.0, 3 * factor, -factor, 0.0], rtol=1e-12)
    np.testing.assert_allclose(scaled.z.acceleration_m_s2, [0.5 * factor, -4 * factor, factor, 0.0], rtol=1e-12)
    assert scaled.y.pga_m_s2 == pytest.approx(0.6 * G, rel=1e-12)
    assert all(m.processing[-1] == {"step": "scale", "factor": pytest.approx(factor, rel=1e-12)}
               for m in scaled.components.values())
    assert scaled.scaling_note == ("Record scaled to the design PGA 0.6 g by one factor 1.961 on every component "
                                   "(its larger horizontal PGA was 0.3059 g).")
    assert MotionPair(x, y, z).scaling_note == ""


def test_one_check_of_the_target_for_a_component_and_a_pair():
    x = GroundMotion.from_array(np.array([0.0, 1.0, -2.0]), 0.01)
    zero = GroundMotion.from_array(np.zeros(3), 0.01)
    pair = MotionPair(x, GroundMotion.from_array(np.array([0.0, 0.5, 0.0]), 0.01))
    for target_g, words in ((60.0, "exceeds 50 g"), (1e-8, "below 1e-06 g"), (-1.0, "not positive")):
        messages = []
        for motion in (x, pair):
            with pytest.raises(errors.MotionError) as caught:
                motion.scaled_to_pga(target_g * G)
            messages.append(str(caught.value))
        assert messages[0] == messages[1] and words in messages[0]
    with pytest.raises(errors.MotionError, match="record of zeros"):
        MotionPair(zero, zero).scaled_to_pga(0.3 * G)
    # a component: 2 m/s² to 0.3 g, factor 0.3 × 9.80665 / 2 = 1.4709975
    scaled = x.scaled_to_pga(0.3 * G)
    assert scaled.processing[-1]["factor"] == pytest.approx(1.4709975, rel=1e-12)
    assert scaled.scaling_note == "Record scaled to the design PGA 0.3 g (from 0.2039 g, factor 1.471)."
    assert x.scaling_note == ""
