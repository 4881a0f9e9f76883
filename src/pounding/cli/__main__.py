"""``python -m pounding.cli``: the same as the ``pounding`` command."""

from . import app

app(prog_name="pounding")
