"""Plotting helpers: compute functions return data, these draw it on a given (or new) ``Axes``.

:mod:`rigidbody.plotting.common` holds what every module uses (axes creation, the unit sphere);
each module may add ``rigidbody.plotting.<module>``. Matplotlib is imported only here.
"""
