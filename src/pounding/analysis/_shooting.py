"""Newton shooting on a stroboscopic map, whatever the system (its map: ``_shooter._Shooter``): the loop, the
residual, the Jacobian (exact where the shooter can propagate the modes, else finite differences)."""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from .._errors import InputError, Problem
from ..engine.layout import A_TSTART, C_T_END, C_T_START, C_V_IN, CONTACT_COLS, N_ACC
from . import _hybrid as hy


class Floquet:
    """What an orbit's result (one mass's or a structure's) says of its ``multipliers``."""

    multipliers: np.ndarray

    @property
    def max_abs_multiplier(self) -> float:
        """The largest ``|multiplier|`` (NaN when there is no monodromy: a search that stopped early)."""
        return float(np.abs(self.multipliers).max()) if self.multipliers.size else math.nan

    @property
    def stable(self) -> bool:
        """Every multiplier inside the unit circle."""
        return self.max_abs_multiplier < 1.0

    def _contact_tables(self) -> list:
        """The orbit run's contact tables (the core's columns): a structure's walls, a pair's links."""
        raise NotImplementedError

    @property
    def period_contact_table(self) -> np.ndarray:
        """The period's contacts, each once, in the order they began, shape (contacts_per_period, 9) (a run's
        ``contact_table`` columns): those that end in it (one in progress at the section is reported whole
        when it ends; one in progress at the end is the same contact again)."""
        return finished_contacts(self._contact_tables())

    @property
    def contacts_per_period(self) -> int:
        """Contacts in one period of the orbit, at every bumper, wall side and link."""
        return int(self.period_contact_table.shape[0])

    @property
    def impact_velocities_m_s(self) -> np.ndarray:
        """Incoming (approach) velocities of the period's contacts in the order they began, m/s, shape
        (contacts_per_period,)."""
        return np.asarray(self.period_contact_table[:, C_V_IN], dtype=float)


def finished_contacts(tables: list) -> np.ndarray:
    """The rows of contact tables (the core's columns) whose contact ended, in the order they began."""
    rows = np.vstack([t for t in tables if len(t)] or [np.zeros((0, CONTACT_COLS))])
    rows = rows[np.isfinite(rows[:, C_T_END])]
    return rows[np.argsort(rows[:, C_T_START], kind="stable")]


def multipliers_of(jac: np.ndarray) -> np.ndarray:
    """The Floquet multipliers of a monodromy ``jac``, largest modulus first (NaN where it is not finite)."""
    finite = jac.size and np.isfinite(jac).all()
    mult = np.linalg.eigvals(jac) if finite else np.full(jac.shape[0], np.nan + 0j)
    return mult[np.argsort(-np.abs(mult), kind="stable")]


def at_section(vec: np.ndarray, layout: dict, n_contacts: int) -> np.ndarray:
    """The state vector moved to time 0 (a whole number of forcing periods back): a contact in
    progress keeps its start relative to the section (``layout``: the core system's)."""
    out = np.array(vec, dtype=float)
    t = out[0]
    for c in range(n_contacts):
        if out[layout["in"] + c]:
            out[layout["acc"] + N_ACC * c + A_TSTART] -= t  # (its running totals' start time)
    out[0] = 0.0
    return out


class _Failed(Exception):
    """A solver's own failure at one point (not the caller's input): the engine could not run a
    period from a trial state, the state is none of the system's, or a parameter value the
    continuation stepped to makes no system."""


class _Newton:
    """Newton shooting on a stroboscopic map, whatever the system: what a shooter shares.  A shooter
    gives ``residual``, ``jacobian``, ``frozen``, ``_layout``, ``_moved``, ``_image``, ``coords``,
    ``_scales``, ``_state`` (a vector as the user's state) and ``_inwards`` (a coordinate at a bound)."""

    scale_d = 1e-3

    def solve(self, vec: np.ndarray, tol: float, max_iter: int) -> tuple:
        """Newton with step halving, each step accepted only where the residual falls (so the
        result is the best iterate): (vector, residual, Jacobian, frozen springs, iterations, message)."""
        try:
            _, r, run = self.residual(vec)
        except _Failed as exc:
            raise InputError(Problem.BAD_STATE, "guess", self._state(vec), why=f"cannot be shot from: {exc}",
                             fix="start from another state, or a smaller a_g") from None
        self.scale_d = self._size_of(run)
        free_idx, _ = self._layout(vec)
        norm = float(np.max(np.abs(r[free_idx]) / self._scales(free_idx)))  # (on the scale just set)
        frozen = self.frozen(vec, run)
        it = 0
        try:
            jac = self.jacobian(vec, run, frozen)
        except _Failed as exc:
            return vec, norm, np.zeros((0, 0)), frozen, it, f"stopped: {exc}"
        while norm > tol and it < max_iter:
            it += 1
            free_idx, emb = self._layout(vec, frozen)
            try:
                dz = np.linalg.solve(jac - np.eye(jac.shape[0]), -r[free_idx])
            except np.linalg.LinAlgError:
                return (vec, norm, jac, frozen, it,
                        "stopped: a multiplier is 1 (a fold or a grazing)" + self.fell_back)
            lam = 1.0
            norm_t = math.inf
            while lam >= 1e-3:
                trial = self._moved(vec, emb @ (lam * dz))
                try:
                    norm_t, r_t, run_t = self.residual(trial)
                except _Failed:  # (a state the system cannot be in, or a run that failed)
                    norm_t = math.inf
                if norm_t < norm:
                    break
                lam *= 0.5
            if not norm_t < norm:
                return (vec, norm, jac, frozen, it,
                        f"stopped: Newton stalled at residual {norm:.1e} (no step along its direction lowers "
                        "it; a grazing or mode change near the section, or tol below what rounding allows)"
                        + self.fell_back)
            vec, r, run, norm = trial, r_t, run_t, norm_t
            frozen = self.frozen(vec, run)
            try:
                jac = self.jacobian(vec, run, frozen)
            except _Failed as exc:
                return vec, norm, np.zeros((0, 0)), frozen, it, f"stopped: {exc}"
        if norm <= tol:
            return (vec, norm, jac, frozen, it,
                    f"converged in {it} Newton iterations (residual {norm:.1e})" + self.fell_back)
        return (vec, norm, jac, frozen, it,
                f"not converged in {it} Newton iterations (residual {norm:.1e} > tol {tol:g})"
                + self.fell_back)

    def residual(self, vec: np.ndarray) -> tuple[float, np.ndarray, Any]:
        """(largest scaled residual over every free coordinate, the residual in ``coords``, the run)."""
        end, run = self._image(vec)
        free_idx, _ = self._layout(vec)
        r = self.coords(end) - self.coords(vec)
        return float(np.max(np.abs(r[free_idx]) / self._scales(free_idx))), r, run

    def jacobian(self, vec: np.ndarray, run: Any, frozen: tuple) -> np.ndarray:
        free_idx, emb = self._layout(vec, frozen)
        if self.exact:
            try:
                full, x_end = self._propagate(vec, run)
                gap = np.abs(x_end - self.coords(run.final_state.vector)).max() / self.scale_d
                if not (np.isfinite(full).all() and gap < 1e-6):
                    raise hy.NoExactMonodromy(f"the modes' propagation ends {gap:.1e} (relative) from the "
                                              "engine")
                return full[free_idx] @ emb
            except hy.NoExactMonodromy as exc:  # (said in the result's message)
                self.exact = False
                self.fell_back = f"; the exact monodromy gave way to finite differences: {exc}"
        return self.differences(vec, free_idx, emb)[free_idx]

    def differences(self, vec: np.ndarray, free_idx: np.ndarray, emb: np.ndarray,
                    step_rel: float = 1e-6) -> np.ndarray:
        """The map's derivatives along each free coordinate (the columns of ``emb``), by finite
        differences of ``step_rel`` times each coordinate's scale: every entry of ``coords`` of the image,
        shape (n, r).  Central, but one-sided (second order, inwards) where the coordinate sits at a bound
        (a compression near 0, z near ``z_max``)."""
        cols = []
        for j, step in enumerate(step_rel * self._scales(free_idx)):
            def image(d: float) -> np.ndarray:
                return self.coords(self._image(self._moved(vec, emb[:, j] * d))[0])

            inwards = self._inwards(vec, int(free_idx[j]), step)
            if inwards:  # a compression (>= 0) or z at its bound: second order, inwards
                d = inwards * step
                cols.append((4.0 * image(d) - image(2.0 * d) - 3.0 * image(0.0)) / (2.0 * d))
            else:
                cols.append((image(step) - image(-step)) / (2.0 * step))
        return np.array(cols).T
