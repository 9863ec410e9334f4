"""One virtual environment per peer library for the scripts under tools/.

A script calls `use_venv(name, packages)` before importing its peer: the first run creates
`tools/.venv-<name>` with the pinned packages, and every run re-executes the script with that
environment's interpreter. `--no-venv` on the command line (or an interpreter already inside
the environment) skips this. CI never runs these scripts; only fixture generation and the
side-by-side benchmarks do.
"""
import os
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))


def use_venv(name, packages):
    venv = os.path.join(HERE, ".venv-" + name)
    py = os.path.join(venv, "bin", "python")
    if "--no-venv" in sys.argv or os.path.realpath(sys.prefix) == os.path.realpath(venv):
        return
    if not os.path.exists(py):
        subprocess.check_call([sys.executable, "-m", "venv", venv])
        subprocess.check_call([py, "-m", "pip", "install", "-q"] + list(packages))
    os.execv(py, [py] + sys.argv)
