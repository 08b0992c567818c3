"""plmap: piecewise-linear maps between simplicial surfaces.

    import numpy as np, plmap
    s1 = plmap.Surface(vertices, triangles)        # (n, 3) float, (m, 3) int; d = 1: (n, 2), (m, 2)
    s2 = plmap.read_surface("s2.off")
    m = plmap.project(s1, s2, max_distance=0.1)    # keyword options: plmap::ProjectionOptions
    m.check()["ok"]                                # the invariant checks, as a dict
    e = m.evaluate(elements, local)                # vectorised, threads, without the GIL
    r = m.regions()                                # flat arrays: parents, corners, measures
    m.save("map.plmap"); plmap.load("map.plmap")
    plmap.load("map.plmapb", s1, s2)              # refuses a map built for other surfaces

Errors of the library are raised as plmap.Error (a ValueError) or one of its subclasses
ParseError, InvalidSurfaceError, BuilderError, InvalidMapError, with the library's message.
See docs/tutorial.md ("From Python").
"""

from ._plmap import (
    BuilderError,
    Error,
    InvalidMapError,
    InvalidSurfaceError,
    Map,
    ParseError,
    Surface,
    __version__,
    load,
    project,
    read_surface,
)

# Shown as plmap.Map, plmap.ParseError, ... rather than under the compiled module's name.
for _public in (BuilderError, Error, InvalidMapError, InvalidSurfaceError, Map, ParseError, Surface):
    _public.__module__ = __name__
del _public

__all__ = [
    "BuilderError",
    "Error",
    "InvalidMapError",
    "InvalidSurfaceError",
    "Map",
    "ParseError",
    "Surface",
    "__version__",
    "load",
    "project",
    "read_surface",
]
