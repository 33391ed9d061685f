"""The environment for a `make` a test runs: run from `make test`, the outer make's flags
(MAKEFLAGS: -w, -j, ...) would leak into it, and -w makes it print "Entering directory" lines
among its output."""
import os

OUTER_MAKE_VARIABLES = ("MAKEFLAGS", "MFLAGS", "MAKELEVEL", "MAKEOVERRIDES")


def clean_make_environment():
    """This process's environment without the outer make's variables."""
    return {name: value for name, value in os.environ.items() if name not in OUTER_MAKE_VARIABLES}
