"""The first-compilation note: one line on stderr when loading an engine is slow, nothing otherwise."""

from __future__ import annotations

import time

from isolator.solver import notice


def test_a_slow_block_is_announced_once(monkeypatch, capsys):
    monkeypatch.setattr(notice, "ENABLED", True)
    with notice.note_if_slow("compiling the engine", after_s=0.05):
        time.sleep(0.5)
    assert capsys.readouterr().err == "note: compiling the engine\n"


def test_a_fast_block_says_nothing(monkeypatch, capsys):
    monkeypatch.setattr(notice, "ENABLED", True)
    with notice.note_if_slow("compiling the engine", after_s=5.0):
        pass
    time.sleep(0.05)
    assert capsys.readouterr().err == ""


def test_the_library_is_silent_unless_the_command_line_asks(monkeypatch, capsys):
    monkeypatch.setattr(notice, "ENABLED", False)
    with notice.note_if_slow("compiling the engine", after_s=0.0):
        time.sleep(0.2)
    assert capsys.readouterr().err == ""


def test_the_command_line_turns_the_notes_on(monkeypatch):
    from typer.testing import CliRunner

    from isolator.cli import app

    monkeypatch.setattr(notice, "ENABLED", False)
    assert CliRunner().invoke(app, ["harmonic", "--alpha", "1.2", "--k", "0", "--eta", "0", "--mu-s", "0.25"]
                              ).exit_code == 0
    assert notice.ENABLED
