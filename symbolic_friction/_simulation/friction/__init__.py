"""Perturbed friction laws for Corollary 1 (eq. perturbed) and the Stribeck
effect (Fig. 4).

The paper's unperturbed friction is ``f_c SGN(v)`` (eq. frictionforceSetValued).
Corollary 1 perturbs it into the *inflated* law

.. math::

    \\mathrm{SGN}_\\rho(v) =
    \\begin{cases}
      [\\operatorname{sign}(v) - \\rho,\\ \\operatorname{sign}(v) + \\rho], & |v| > \\rho,\\\\
      [-1 - \\rho,\\ 1 + \\rho], & |v| \\le \\rho,
    \\end{cases}
    \\qquad \\mathrm{SGN}_\\rho(v) = \\mathrm{SGN}(v + \\rho\\mathbb B) + \\rho\\mathbb B,

and states ISS of 𝒜 from the input ρ.  A Stribeck law whose graph lies inside
``f_c SGN_ρ`` (Fig. 4) is one of the dynamics covered.

All laws here are simulated by the ``moreau`` method (implicit Euler,
:mod:`..moreau`): pass one as ``simulate(..., method="moreau", friction=law)``.
In one implicit Euler step of size ``h`` the whole inclusion reduces to a
*scalar* inclusion in the next velocity ``w = v_{n+1}`` (see :class:`Step`):

.. math::

    D\\,w + h\\,f \\ni r,\\qquad f \\in F(w),\\qquad
    D = 1 + h k_v + h^2 k_p + h^3 k_i,\\quad r = v_n + h\\phi_n + h^2\\sigma_n,

where ``F`` is the friction graph (force per unit mass).  Each law solves
this scalar inclusion in :meth:`FrictionLaw.solve_step`.

The laws: :class:`Coulomb` (the paper's), :class:`InflatedCoulomb`
(Corollary 1's ``SGN_ρ`` with a selection, :mod:`.inflated`) and
:class:`Stribeck` (Fig. 4, :mod:`.stribeck`), each a :class:`FrictionLaw`
(:mod:`._law`).
"""

from __future__ import annotations

from ._law import WORST_CASE, Coulomb, FrictionLaw, Step
from .inflated import InflatedCoulomb
from .stribeck import Stribeck

__all__ = ["Step", "FrictionLaw", "Coulomb", "InflatedCoulomb", "Stribeck", "WORST_CASE"]
