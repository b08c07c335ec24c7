"""isolator.parallel: one pool for maps and batch; results come back in the order of the items."""

from __future__ import annotations

import os

import pytest

from isolator.parallel import available_cores, default_workers, map_interleaved


def _square_all(items):
    return [(item, item * item, os.getpid()) for item in items]


def test_default_workers_is_within_the_cores():
    assert 1 <= default_workers() <= available_cores() <= (os.cpu_count() or 1)


def test_map_interleaved_keeps_the_order_in_and_out_of_process():
    items = list(range(37))
    serial = map_interleaved(_square_all, items, workers=1)
    assert [r[:2] for r in serial] == [(i, i * i) for i in items]
    assert {r[2] for r in serial} == {os.getpid()}
    pooled = map_interleaved(_square_all, items, workers=2, chunks_per_worker=3)
    assert [r[:2] for r in pooled] == [(i, i * i) for i in items]  # interleaved chunks put back in order
    assert os.getpid() not in {r[2] for r in pooled}  # computed by the pool's processes


def _square(x):
    return x * x


@pytest.mark.parametrize("jobs", [1, 2])
def test_iterate_runs_every_task_once_locally(jobs):
    from isolator.parallel import iterate

    got = dict(iterate(list(range(7)), _square, jobs=jobs))
    assert got == {i: i * i for i in range(7)}
