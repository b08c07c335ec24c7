"""Target spectra: the ASCE two-period shape, design values, EN 1998-1, a CSV table, and file mistakes."""

from __future__ import annotations

import numpy as np
import pytest

from isolator.errors import TargetError
from isolator.review.target import load_target, two_period_target


def test_two_period_shape_by_hand():
    t = two_period_target(1.5, 0.9, 8.0)  # T_0 = 0.12 s, T_S = 0.6 s
    periods = [0.0, 0.06, 0.12, 0.6, 1.0, 8.0, 10.0]
    np.testing.assert_allclose(t.sa_g(periods), [0.6, 1.05, 1.5, 1.5, 0.9, 0.9 / 8.0, 0.9 * 8.0 / 100.0])


def test_files(tmp_path):
    (tmp_path / "d.toml").write_text("S_DS = 1.0\nS_D1 = 0.6\nT_L = 8\n")
    assert load_target(tmp_path / "d.toml").sa_g([1.0])[0] == pytest.approx(0.9)  # 1.5 × S_D1 / T
    (tmp_path / "en.toml").write_text("a_g_g = 0.3\nS = 1.2\nT_B = 0.15\nT_C = 0.5\nT_D = 2.0\n")
    en = load_target(tmp_path / "en.toml")
    np.testing.assert_allclose(en.sa_g([0.0, 0.3, 1.0, 4.0]), 0.36 * np.array([1.0, 2.5, 1.25, 2.5 * 0.5 * 2 / 16]))
    (tmp_path / "s.csv").write_text("period_s,sa_g\n0.1,1.0\n1.0,0.5\n10.0,0.05\n")
    (tmp_path / "c.toml").write_text('spectrum_csv = "s.csv"\n')
    table = load_target(tmp_path / "c.toml")
    assert table.sa_g([1.0])[0] == pytest.approx(0.5)
    assert table.sa_g([np.sqrt(10.0)])[0] == pytest.approx(np.sqrt(0.5 * 0.05))  # log-log interpolation
    with pytest.raises(TargetError, match="covers 0.1–10 s"):
        table.sa_g([20.0])


@pytest.mark.parametrize("text, words", [
    ("S_MS = 1.5\nS_M1 = 0.9\n", "missing key 'T_L'"),
    ("S_MS = 1.5\nS_M1 = 0.9\nT_L = 8\nspectrum_csv = 'x.csv'\n", "exactly one target"),
    ("S_MS = -1\nS_M1 = 0.9\nT_L = 8\n", "'S_MS' must be a number > 0"),
    ("S_MS = 1.5\nS_M1 = 0.9\nT_L = 0.3\n", "must exceed T_S"),
    ("SMS = 1.5\n", "unknown key 'SMS'"),
    ("spectrum_csv = 'absent.csv'\n", "no such file"),
])
def test_target_mistakes_are_one_line(tmp_path, text, words):
    path = tmp_path / "t.toml"
    path.write_text(text)
    with pytest.raises(TargetError) as info:
        load_target(path)
    assert words in str(info.value) and str(path) in str(info.value) and "\n" not in str(info.value)


def test_controlling_ranges_and_mechanisms(tmp_path):
    from isolator.errors import TargetError
    from isolator.review.target import load_target

    path = tmp_path / "t.toml"
    path.write_text('S_MS = 1.5\nS_M1 = 0.9\nT_L = 8.0\nmagnitude_range = [6.5, 7.5]\nvs30_m_s_range = [180, 360]\n'
                    'mechanisms = ["strike-slip", "reverse"]\n')
    target = load_target(path)
    assert target.controlling == {"magnitude_range": [6.5, 7.5], "vs30_m_s_range": [180.0, 360.0],
                                  "mechanisms": ["strike-slip", "reverse"]}
    assert target.as_dict()["mechanisms"] == ["strike-slip", "reverse"] and target.sa_g(1.0)[0] == 0.9
    for bad, words in (("magnitude_range = [7.5, 6.5]", "must be \\[low, high\\]"), ("mechanisms = []", "list of texts")):
        path.write_text(f"S_MS = 1.5\nS_M1 = 0.9\nT_L = 8.0\n{bad}\n")
        with pytest.raises(TargetError, match=words):
            load_target(path)
