"""Every public function and class points to its neighbours (numpydoc's See Also section).

A reader who lands on one API page finds the functions that do the related job: the other route to the same
number, the object it returns or takes, the lower-level function it wraps. The public objects are those listed
in the ``__all__`` of a public module (the same set the API pages document).
"""

from __future__ import annotations

import importlib
import inspect

from tests.docs.test_member_examples import PUBLIC_MODULES

# Objects whose See Also waits for a change that makes room for it (none now). A name put here leaves it when its See
# Also is written: the second test fails on a name that no longer waits.
WAITING: set[str] = set()


def public_objects() -> dict[str, object]:
    found: dict[str, object] = {}
    for module_name in PUBLIC_MODULES:
        module = importlib.import_module(module_name)
        for name in getattr(module, "__all__", ()):
            obj = getattr(module, name)
            if (inspect.isclass(obj) or inspect.isfunction(obj)) and obj.__module__.startswith("rigidbody."):
                if all(obj is not seen for seen in found.values()):  # the first public module that lists it
                    found[f"{module_name}.{name}"] = obj
    return found


def test_every_public_function_and_class_has_a_see_also_section() -> None:
    objects = public_objects()
    missing = sorted(name for name, obj in objects.items()
                     if "See Also\n" not in (inspect.getdoc(obj) or "") and name not in WAITING)
    assert not missing, f"add a See Also section to {missing}"


def test_the_waiting_list_names_only_objects_still_without_one() -> None:
    objects = public_objects()
    done = sorted(name for name in WAITING
                  if name not in objects or "See Also\n" in (inspect.getdoc(objects[name]) or ""))
    assert not done, f"remove from WAITING (written or gone): {done}"
