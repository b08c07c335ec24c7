"""Typed errors of the review (messages: one line naming the file or the key and the problem)."""

from __future__ import annotations


class ReviewError(ValueError):
    """A review input (target, suite, parameter) that cannot be used."""


class TargetError(ReviewError):
    """An invalid target spectrum file."""


class SuiteError(ReviewError):
    """An invalid suite (file, pair, duplicate, mismatched components)."""
