"""Matplotlib for the project's plot scripts, or a clear word that it is
missing.

The scripts start with '#!/usr/bin/env python3': the python3 first on PATH
runs them, which may be one without matplotlib (a virtual environment, a
pyenv or conda python). A script that also checks a run must still check
it then: pyplot() returns None after saying what is missing and how to get
it, and the script skips only its figures.

    from immersedDEMFigure import pyplot
    plt = pyplot("plotPile")
    if plt is not None:
        fig, ax = plt.subplots()
"""
import sys


def pyplot(script, checksFollow=True):
    """matplotlib.pyplot on the file-only Agg backend, or None (with a
    message on stderr naming the python, the cause and the remedy)."""
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        return plt
    except ImportError as e:
        other = "" if sys.executable == "/usr/bin/python3" else \
            ", or run the script with a python that has it (e.g. /usr/bin/python3 %s)" % script
        sys.stderr.write(
            "%s: no figures written: the python running it (%s) cannot import matplotlib (%s). "
            "Install it (Debian: apt-get install python3-matplotlib; or: %s -m pip install matplotlib)%s.%s\n"
            % (script, sys.executable, e, sys.executable, other,
               " Its checks still run." if checksFollow else ""))
        sys.stderr.flush()
        return None
