"""Code-based design review of a friction isolation system over a scaled ground-motion suite.

``run_review(design, target, suite, code=…, scaling=…, jobs=…) -> Review`` (:mod:`isolator.review.run`);
the suite (:mod:`.suite`), target (:mod:`.target`), spectra (:mod:`.spectra`), scaling (:mod:`.scaling`),
property bounds (:mod:`.bounds`), code clauses (:mod:`.codes`), checks (:mod:`.checks`, :mod:`.assess`).
Imports are lazy so that ``isolator --help`` stays fast.
"""

from __future__ import annotations

__all__ = ["load_suite", "load_target", "resolve_example", "run_review"]


def __getattr__(name):
    if name == "run_review":
        from isolator.review.run import run_review

        return run_review
    if name == "load_suite":
        from isolator.review.suite import load_suite

        return load_suite
    if name == "load_target":
        from isolator.review.target import load_target

        return load_target
    if name == "resolve_example":
        from isolator.review.examples import resolve_example

        return resolve_example
    raise AttributeError(name)
