"""The methods and properties of the public classes show an example, as the functions do.

A public class is one listed in the ``__all__`` of a public module (no component of its name starts with an
underscore); its members are those defined in its own body with a public name. A member with a docstring of its
own needs an Examples section (tests/test_doctests.py runs it); one without a docstring shows its base class's
on the API page (autodoc inherits docstrings), which is checked where it is defined.
"""

from __future__ import annotations

import importlib
import inspect
import pkgutil

import rigidbody

PUBLIC_MODULES = [info.name for info in pkgutil.walk_packages(rigidbody.__path__, f"{rigidbody.__name__}.")
                  if not any(part.startswith("_") for part in info.name.split("."))]

# Members whose Examples wait for a change that makes room for them (none now). Remove a name from here when its
# example is written (the test then holds it).
WAITING: set[str] = set()


def public_classes() -> dict[str, type]:
    found: dict[str, type] = {}
    for module_name in PUBLIC_MODULES:
        module = importlib.import_module(module_name)
        for name in getattr(module, "__all__", ()):
            obj = getattr(module, name)
            if inspect.isclass(obj) and obj.__module__.startswith("rigidbody."):
                found.setdefault(f"{module_name}.{name}", obj)  # the first public module that lists it names it
    return found


def documented_members() -> dict[str, str]:
    """``{qualified name: own docstring}`` of the public methods and properties of the public classes."""
    members: dict[str, str] = {}
    seen: set[type] = set()
    for class_name, cls in public_classes().items():
        if cls in seen:
            continue
        seen.add(cls)
        for name, attr in vars(cls).items():
            if name.startswith("_"):
                continue
            fn = attr.__func__ if isinstance(attr, (staticmethod, classmethod)) else attr
            fn = fn.fget if isinstance(fn, property) else fn
            if inspect.isfunction(fn) and fn.__doc__:
                members[f"{class_name}.{name}"] = fn.__doc__
    return members


def test_every_documented_member_has_an_example() -> None:
    members = documented_members()
    missing = sorted(name for name, doc in members.items() if "Examples\n" not in doc and name not in WAITING)
    assert not missing, f"add an Examples section to {missing}"
    # a name that got its example (or was renamed) leaves the waiting list, so the list cannot hide a new gap
    stale = sorted(name for name in WAITING if name not in members or "Examples\n" in members[name])
    assert not stale, f"remove from WAITING: {stale}"


def test_the_walk_sees_the_classes_and_their_members() -> None:
    # guards the test above against passing vacuously
    members = documented_members()
    assert "rigidbody.core.ode.Solution.plot" in members
    assert "rigidbody.euler_poinsot.EulerPoinsot.period" in members  # a property
    assert "rigidbody.euler_poinsot.EulerPoinsot.from_GT" in members  # a classmethod
    assert "rigidbody.lagrange.LinearDrag.body_moments_batch" in members
