"""Random hostile input through all three engines (tests/fuzz.py says what
is generated and what must hold). A few hundred cases in the default suite,
thousands in the slow one; a finding names the case, its mutation and what
each engine did."""

import pytest
from fuzz import run_cases


def check(report):
    print({k: v for k, v in report.items() if k != "findings"})
    assert report["findings"] == [], "\n".join(report["findings"][:20])


def test_fuzz(tmp_path):
    check(run_cases(300, seed=20261123, directory=tmp_path))


@pytest.mark.slow
@pytest.mark.parametrize("seed", range(10))
def test_fuzz_many(seed, tmp_path):
    check(run_cases(300, seed=seed, directory=tmp_path))
