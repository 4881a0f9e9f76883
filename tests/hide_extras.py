"""Imported first in a subprocess: the modules only an optional extra installs are hidden from there on
(``extras_hidden.install``)."""

from extras_hidden import install

install()
