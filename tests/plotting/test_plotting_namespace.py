"""rigidbody.plotting exposes every helper of its submodules at the top level."""

import importlib

import rigidbody.plotting as P


def test_every_submodule_helper_is_at_the_top_level():
    for sub in ("common", "euler_poinsot", "gyrostat", "lagrange", "studies", "viscous"):
        mod = importlib.import_module(f"rigidbody.plotting.{sub}")
        for name in mod.__all__:
            assert name in P.__all__, f"rigidbody.plotting.{sub}.{name} is not exported by rigidbody.plotting"
            assert getattr(P, name) is getattr(mod, name)
