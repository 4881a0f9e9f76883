"""Hypothesis profiles: random examples on developers' machines (they keep exploring, and
.hypothesis/ remembers what failed), the same examples every time in CI (``CI=true``), so that
a landing does not depend on the draw: a new failure found locally becomes a regression test."""

import os
import signal

from hypothesis import settings

settings.register_profile("ci", derandomize=True, database=None)
if os.environ.get("CI", "").lower() in ("1", "true", "yes"):
    settings.load_profile("ci")

# A run started with SIGINT ignored (a background job of a shell without job control) never turns
# Ctrl-C into KeyboardInterrupt, which the Ctrl-C tests send themselves: Python's own handler back
if signal.getsignal(signal.SIGINT) is signal.SIG_IGN:
    signal.signal(signal.SIGINT, signal.default_int_handler)
