"""Test configuration shared by the whole suite.

* Matplotlib draws off-screen (Agg).
* Hypothesis runs derandomised (a fixed seed): the same examples on every run and in CI, so a failure
  is reproducible. ``HYPOTHESIS_PROFILE=explore`` runs randomised with more examples.
"""

import os

import matplotlib

matplotlib.use("Agg")

from hypothesis import HealthCheck, settings

settings.register_profile(
    "ci", derandomize=True, deadline=None, print_blob=True, suppress_health_check=[HealthCheck.too_slow]
)
settings.register_profile("explore", max_examples=500, deadline=None)
settings.load_profile(os.environ.get("HYPOTHESIS_PROFILE", "ci"))
