"""Axis labels that several figures share, each written once: a quantity, then its unit in brackets
(``[-]`` for a ratio)."""

A_G_LABEL = "a_G = A_t / g [-]"  # the table's peak acceleration in g: a ratio, as the paper's tables give it
