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
