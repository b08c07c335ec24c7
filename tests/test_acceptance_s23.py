"""Issues 22 and 23 read as acceptance tests (h218, docs/review.md): what the batch table keeps of the schema."""
import json

from isolator.batch.store import COLUMNS, model_columns


def test_batch_keeps_each_regimes_first_time_and_the_ultimate_time():
    # issue 23: `regimes` is {"I": first time [s], …}; the batch row used to keep only the names.  The truth is the
    # analysis' own dict (given out of order here: the row lists the regimes in order of entry).
    regimes = {"III": 3.25, "I": 0.125, "V": 7.5, "II": 1.0000000000000002, "IV": 6.0}
    row = model_columns({"regimes": regimes, "ultimate_first_time_s": 7.5, "bearing_type": "triple"})
    assert row["regimes_reached"] == "I, II, III, IV, V"
    kept = json.loads(row["regimes_first_time_s"])
    assert list(kept) == ["I", "II", "III", "IV", "V"] and kept == regimes  # every time to the last bit
    assert row["ultimate_first_time_s"] == 7.5
    assert {"regimes_first_time_s", "ultimate_first_time_s"} <= set(COLUMNS)
    # a double names its sliding surfaces; a run that never reaches the ultimate leaves the column empty
    row = model_columns({"regimes": {"1+2": 26.182994229404322}, "ultimate_first_time_s": None})
    assert json.loads(row["regimes_first_time_s"]) == {"1+2": 26.182994229404322}
    assert "ultimate_first_time_s" not in row


def test_stability_does_not_pass_beside_a_bearing_beyond_its_displacement_capacity():
    """h218: `vertical_load_stability` passed at 0.694 × capacity while corner bearings reached 1.467–1.562 m of a
    1.4 m capacity (`record_capacity` failing): the capacity is stated at the total displacement, so the row is
    `not checked`, saying why; a failing stability row stays failing, and with the displacements within capacity the
    row is untouched."""
    from isolator.review import checks as C
    from isolator.review.assess import no_stability_pass_beyond_capacity

    stability = C.vertical_load_stability([4.0e6, 5.0e6], [7.2e6, 7.2e6], clause="ASCE 7-22 17.2.4.6")
    assert stability["status"] == C.PASS and abs(stability["value"] - 5.0 / 7.2) < 1e-15
    beyond = [C.check("record_capacity", "ASCE 7-22 17.2.4.5", C.FAIL, 1.562, 1.4, "pair 1 (upper)", "m"),
              C.check("record_capacity", "ASCE 7-22 17.2.4.5", C.FAIL, 1.467, 1.4, "pair 2 (upper)", "m")]
    out = no_stability_pass_beyond_capacity([*beyond, stability])
    assert out[:2] == beyond
    assert out[2]["status"] == C.NOT_CHECKED and out[2]["value"] == stability["value"]
    assert out[2]["note"].endswith("; would pass, but 2 analysis(es) take a bearing beyond its displacement capacity "
                                   "(record_capacity), where the axial capacity, stated at the total displacement, "
                                   "does not apply")
    failing = C.vertical_load_stability([8.0e6], [7.2e6], clause="ASCE 7-22 17.2.4.6")
    assert no_stability_pass_beyond_capacity([*beyond, failing])[2] == failing
    within = [C.check("record_capacity", "ASCE 7-22 17.2.4.5", C.PASS, 1.2, 1.4, "largest", "m"), stability]
    assert no_stability_pass_beyond_capacity(within) == within


def test_the_2d_triple_reason_names_the_vertical_it_runs_with():
    """h218: `2d-multisurface+vertical`'s model_reason said "under two horizontal components" and left out the
    vertical its name carries."""
    from types import SimpleNamespace

    from isolator.bearing import parse_bearing
    from isolator.errors import DesignError
    from isolator.solver.planar_multisurface import scene_needs

    tfp = parse_bearing({"type": "triple", "surface": [
        {"radius_m": r, "mu": m, "displacement_capacity_m": d}
        for r, m, d in ((2.1, 0.06, 0.8), (0.3, 0.02, 0.05), (0.3, 0.02, 0.05), (2.1, 0.10, 0.8))]}, DesignError)
    said = {(y, z): scene_needs(SimpleNamespace(design=SimpleNamespace(bearing=tfp), has_y=y, has_z=z))
            for y, z in ((True, False), (True, True), (False, True))}
    assert said[True, True][0] == "2d-multisurface+vertical"
    assert "(4 surfaces) under two horizontal components and a vertical: " in said[True, True][1]
    assert "(4 surfaces) under two horizontal components: " in said[True, False][1]
    assert "(4 surfaces) under a vertical component: " in said[False, True][1]
    assert scene_needs(SimpleNamespace(design=SimpleNamespace(bearing=tfp), has_y=False, has_z=False)) is None
