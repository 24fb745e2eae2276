"""Binding obligations ``model.*_runtime``: each holds, and each fails when
the runtime function it binds is broken in one place (in one kind only, or
in the symbolic form only)."""

import dataclasses
from fractions import Fraction

import numpy as np
import pytest
import sympy as sp

from symbolic_friction._model.attractor import squared_distance_x, squared_distance_z
from symbolic_friction._model.lyapunov import V, V_hat, in_R
from symbolic_friction._obligations import all_obligations
from symbolic_friction._obligations._decide import G
from symbolic_friction._obligations.model import (
    INSTANCE,
    K_INSTANCE,
    DistanceRuntime,
    DistanceZRuntime,
    HatVRateRuntime,
    KindsRuntime,
    HatVRuntime,
    MatricesRuntime,
    ModesRuntime,
    PNormRuntime,
    RRuntime,
    VRuntime,
    instance_points,
)

from ._helpers import assert_fails, assert_holds, obligation_fixture

g = G()

v_runtime = obligation_fixture(VRuntime)
hatv_runtime = obligation_fixture(HatVRuntime)
r_runtime = obligation_fixture(RRuntime)
distance_runtime = obligation_fixture(DistanceRuntime)
distance_z_runtime = obligation_fixture(DistanceZRuntime)
matrices_runtime = obligation_fixture(MatricesRuntime)
modes_runtime = obligation_fixture(ModesRuntime)
pnorm_runtime = obligation_fixture(PNormRuntime)


def test_every_binding_is_listed_by_check():
    ids = [ob.id for ob in all_obligations()]
    for cls in (VRuntime, HatVRuntime, RRuntime, DistanceRuntime, DistanceZRuntime, MatricesRuntime, ModesRuntime, PNormRuntime):
        assert cls.id in ids


def test_instance_points_cover_every_class_and_boundary():
    points = instance_points()
    assert len(points) == 63
    phis = {p[1] for p in points}
    assert {INSTANCE.f_c, -INSTANCE.f_c} <= phis  # both boundaries of dz and of the table
    assert {np.sign(float(p[2])) for p in points} == {-1.0, 0.0, 1.0}


@pytest.mark.parametrize(
    "fixture",
    ["v_runtime", "hatv_runtime", "r_runtime", "distance_runtime", "distance_z_runtime", "matrices_runtime", "modes_runtime", "pnorm_runtime"],
)
def test_binding_holds(fixture, request):
    ob, subject = request.getfixturevalue(fixture)
    assert_holds(ob, subject)


# ---------------------------------------------------------------- V


def _v_zero_at_rest(p, x):
    """Exact V with the friction value 0 at v = 0 instead of the projection of φ."""
    sigma, phi, v = x
    return V(p, x) if v != 0 else V(p, [sigma, Fraction(0), v]) + phi**2


def test_V_wrong_minimiser_symbolic_fails(v_runtime):
    ob, s = v_runtime
    wrong = V(g, [g.sigma, g.phi, 0 * g.v]).subs(g.phi, 0) + g.phi**2  # f = 0 instead of sat(φ) at v = 0
    broken = sp.Piecewise((s.symbolic, sp.Ne(g.v, 0)), (wrong, True))
    assert_fails(ob, dataclasses.replace(s, symbolic=broken), "v = 0", "differs from the paper")


def test_V_wrong_exact_kind_fails(v_runtime):
    ob, s = v_runtime
    assert_fails(ob, dataclasses.replace(s, exact=_v_zero_at_rest), "the exact V")


def test_V_wrong_float_kind_fails(v_runtime):
    ob, s = v_runtime

    def float_v(p, x):
        out = np.array(V(p, x), dtype=float)
        return out + (x[:, 2] == 0) * 1.0  # off by one at rest
    assert_fails(ob, dataclasses.replace(s, floats=float_v), "the float V")


def test_V_exact_kind_returning_a_float_fails(v_runtime):
    ob, s = v_runtime
    assert_fails(ob, dataclasses.replace(s, exact=lambda p, x: float(V(p, x))), "the exact V")


# ---------------------------------------------------------------- V̂


def test_hatV_doubled_cross_term_fails(hatv_runtime):
    ob, s = hatv_runtime
    k3 = sp.Symbol("k_3", positive=True)
    broken = s.symbolic + k3 * sp.Abs(g.sigma) * sp.Abs(g.v)
    assert_fails(ob, dataclasses.replace(s, symbolic=broken), "differs from the paper")


def test_hatV_without_dead_zone_fails_in_exact_kind(hatv_runtime):
    ob, s = hatv_runtime

    def no_dz(p, x):
        sigma, phi, v = x
        k1, k2, k3, k4 = K_INSTANCE
        return k1 * sigma**2 / 2 + k2 * phi**2 / 2 + k3 * abs(sigma) * abs(v) + k4 * v**2 / 2

    assert_fails(ob, dataclasses.replace(s, exact=no_dz), "the exact V̂")


def test_hatV_float_kind_off_fails(hatv_runtime):
    ob, s = hatv_runtime
    assert_fails(ob, dataclasses.replace(s, floats=lambda p, x: V_hat(p, x, K_INSTANCE) * 1.5), "the float V̂")


# ---------------------------------------------------------------- R


def test_R_strict_fails(r_runtime):
    ob, s = r_runtime
    strict = sp.StrictGreaterThan(s.symbolic.lhs, 0)
    assert_fails(ob, dataclasses.replace(s, symbolic=strict), "x ∈ R")


def test_R_sign_flip_fails(r_runtime):
    ob, s = r_runtime
    flipped = sp.GreaterThan(g.v * (g.phi + sp.sign(g.v) * g.f_c), 0)
    assert_fails(ob, dataclasses.replace(s, symbolic=flipped), "the paper")


def test_R_strict_float_kind_fails(r_runtime):
    ob, s = r_runtime
    from symbolic_friction._model.lyapunov import R_margin

    assert_fails(ob, dataclasses.replace(s, floats=lambda p, x: R_margin(p, x) > 0), "the float x ∈ R")


def test_R_exact_kind_not_a_bool_fails(r_runtime):
    ob, s = r_runtime
    assert_fails(ob, dataclasses.replace(s, exact=lambda p, x: int(in_R(p, x))), "the exact x ∈ R")


# ---------------------------------------------------------------- distances


def test_distance_without_v_fails(distance_runtime):
    ob, s = distance_runtime
    assert_fails(ob, dataclasses.replace(s, symbolic=s.symbolic - g.v**2), "differs from the paper")


def test_distance_float_kind_off_fails(distance_runtime):
    ob, s = distance_runtime
    assert_fails(
        ob, dataclasses.replace(s, floats=lambda p, x: squared_distance_x(p, x) + (np.abs(x[:, 1]) == 2)), "the float |x|²_𝒜"
    )


def test_distance_z_wrong_bound_fails(distance_z_runtime):
    ob, s = distance_z_runtime
    assert_fails(
        ob,
        dataclasses.replace(s, exact=lambda p, z: squared_distance_z(p, z) + (abs(z[0]) > 1) * (z[0] ** 2 - (abs(z[0]) - 1) ** 2)),
        "the exact |z|²_𝒜",
    )


# ---------------------------------------------------------------- matrices, modes, |y|_P


def test_matrices_swapped_gains_fail(matrices_runtime):
    ob, s = matrices_runtime
    from symbolic_friction._model.coordinates import system_matrix_entries

    swapped = lambda p: np.array(system_matrix_entries(float(p.k_v), float(p.k_i), float(p.k_p)))  # noqa: E731
    assert_fails(ob, dataclasses.replace(s, runtime={**s.runtime, "A": swapped}), "A[")


def test_matrices_inexact_coordinate_map_fails(matrices_runtime):
    ob, s = matrices_runtime
    assert_fails(
        ob, dataclasses.replace(s, runtime={**s.runtime, "T (exact)": lambda p: np.eye(3)}), "T (exact)"
    )


def test_modes_wrong_boundary_fails(modes_runtime):
    ob, s = modes_runtime

    def select_mode(sigma, phi, v, f_c, *f_s):  # row (v) sent to k = -1 instead of 0
        k = s.select_mode(sigma, phi, v, f_c, *f_s)
        return -1 if (v == 0 and phi == f_c and sigma < 0) else k

    assert_fails(ob, dataclasses.replace(s, select_mode=select_mode), "select_mode gives k = -1", "row (v)")


def test_modes_unreached_row_fails(modes_runtime):
    ob, s = modes_runtime
    few = tuple(p for p in s.points if p[2] != 0)
    assert_fails(ob, dataclasses.replace(s, points=few), "never reached")


def test_pnorm_sign_flip_fails(pnorm_runtime):
    ob, s = pnorm_runtime

    def wrong(sv, p, v, kv_ki, k_p):
        return float(np.sqrt(kv_ki * sv * sv + 2.0 * sv * v + k_p * v * v + p * p))

    assert_fails(ob, dataclasses.replace(s, p_norm=wrong), "p_norm²")


def test_modes_at_rest_strict_boundary_fails(modes_runtime):
    ob, s = modes_runtime

    def mode_at_rest(sigma, base, offset, f_c, tol, excess=0.0):  # rows (iii)-(v) decided by the sign of the offset only
        b, o, k = s.mode_at_rest(sigma, base, offset, f_c, tol, excess)
        phi = base * f_c + offset
        return (b, o, 0) if phi == f_c else (b, o, k)

    assert_fails(ob, dataclasses.replace(s, mode_at_rest=mode_at_rest), "mode_at_rest gives k = 0", "row (iii)")


def test_mode_after_slip_without_the_clamp_rule_fails(modes_runtime):
    ob, s = modes_runtime

    def mode_after_slip(sigma, offset, direction, f_c, tol, excess=0.0):  # clamps the side a slip can end on
        return s.mode_at_rest(sigma, direction, 0.0 if direction * offset < 0 else offset, f_c, tol, excess)

    assert_fails(ob, dataclasses.replace(s, mode_after_slip=mode_after_slip), "after a slip d = ", "mode_after_slip")


hatv_rate_runtime = obligation_fixture(HatVRateRuntime)


def test_hatV_rate_holds(hatv_rate_runtime):
    assert_holds(*hatv_rate_runtime)


def test_hatV_rate_without_clarke_max_fails(hatv_rate_runtime):
    ob, s = hatv_rate_runtime
    from symbolic_friction._model.lyapunov import V_hat_rate

    def smooth_only(p, x):  # sign(σ)σ' also at σ = 0, i.e. 0 instead of |σ'|
        value = V_hat_rate(p, x, K_INSTANCE)
        sigma, phi, v = x
        if sigma != 0:
            return value
        k3 = K_INSTANCE[2]
        return value - k3 * abs(p.k_i * v) * abs(v)

    assert_fails(ob, dataclasses.replace(s, exact=smooth_only), "the exact V̂°")


def test_hatV_rate_wrong_flow_fails(hatv_rate_runtime):
    ob, s = hatv_rate_runtime
    k4 = sp.Symbol("k_4", positive=True)
    assert_fails(ob, dataclasses.replace(s, symbolic=s.symbolic + k4 * g.v * g.f_c * sp.sign(g.v)), "differs from the paper")


kinds_runtime = obligation_fixture(KindsRuntime)


def test_kinds_hold(kinds_runtime):
    assert_holds(*kinds_runtime)


@pytest.mark.parametrize("op", ["sign", "clip", "abs", "where"])
def test_each_broken_kind_operation_fails(kinds_runtime, op):
    ob, s = kinds_runtime
    from symbolic_friction._model.kinds import EXACT

    class Broken(type(EXACT)):
        name = "exact"

        def sign(self, y):
            return super().sign(y) if op != "sign" else (y > 0) - (y <= 0)

        def clip(self, y, lo, hi):
            return super().clip(y, lo, hi) if op != "clip" else super().clip(y, lo, 2 * hi)

        def abs(self, y):
            return super().abs(y) if op != "abs" else y

        def where(self, cond, a, b):
            return super().where(cond, a, b) if op != "where" else super().where(not cond, a, b)

    assert_fails(ob, dataclasses.replace(s, kinds=(Broken(),)), f"exact kind's {op}(")


def test_each_obligation_module_is_named_after_its_id_prefix():
    """One module per id prefix; the registry lists exactly the modules' obligations, each once."""
    from symbolic_friction._obligations import obligation_modules, registry

    listed = []
    for module in obligation_modules():
        prefix = module.__name__.rsplit(".", 1)[1]
        assert module.OBLIGATIONS, prefix
        for cls in module.OBLIGATIONS:
            assert cls.id.split(".")[0] == prefix, (prefix, cls.id)
            listed.append(cls)
    assert sorted(c.__name__ for c in listed) == sorted(c.__name__ for c in registry())
    assert len(set(registry())) == len(registry())


def test_a_missing_obligation_module_is_an_import_error(monkeypatch):
    """A registered module that cannot be imported stops the run; it is never skipped."""
    import sys

    import symbolic_friction._obligations as obligations

    monkeypatch.setitem(sys.modules, "symbolic_friction._obligations.table1", None)
    monkeypatch.delattr(obligations, "table1", raising=False)
    with pytest.raises(ImportError):
        obligations.all_obligations()


def test_pnorm_tolerance_is_pinned(pnorm_runtime):
    """A p_norm off by twice the named tolerance fails (so a 2⁴⁰ looser tolerance would be caught); half of it holds."""
    from fractions import Fraction

    from symbolic_friction._obligations.model import P_NORM_TOLERANCE

    ob, s = pnorm_runtime
    assert P_NORM_TOLERANCE == Fraction(8, 2**52)
    for factor, fails in ((2.0, True), (0.25, False)):
        bump = 1.0 + factor * float(P_NORM_TOLERANCE) / 2  # relative error on the square ≈ factor·tolerance

        def off(sv, p, v, kv_ki, k_p, bump=bump):
            return s.p_norm(sv, p, v, kv_ki, k_p) * bump

        if fails:
            assert_fails(ob, dataclasses.replace(s, p_norm=off), "p_norm²", "allowed")
        else:
            assert_holds(ob, dataclasses.replace(s, p_norm=off))


def test_pnorm_at_a_scaled_state_only_fails(pnorm_runtime):
    """A p_norm right at unit scale but wrong at 1e6 (a factor dropped for large states) fails."""
    ob, s = pnorm_runtime

    def wrong(sv, p, v, kv_ki, k_p):
        value = s.p_norm(sv, p, v, kv_ki, k_p)
        return value * (1.001 if max(abs(sv), abs(p), abs(v)) > 1e3 else 1.0)

    assert_fails(ob, dataclasses.replace(s, p_norm=wrong), "p_norm²")


def test_float_V_right_only_at_the_instance_f_c_fails(v_runtime):
    """A float V that reads f_c from the instance (f_c = 2) instead of its parameters: the scaled f_c catch it."""
    from symbolic_friction._obligations.model import INSTANCE

    ob, s = v_runtime
    assert_fails(ob, dataclasses.replace(s, floats=lambda p, X: V(INSTANCE, X)), "the float V", "scaled from f_c")


def test_exact_R_with_f_c_dropped_fails(r_runtime):
    """x ∈ R tested with f_c = 1 in the exact kind (a dropped factor, invisible at f_c = 1)."""
    from symbolic_friction._model.parameters import Parameters

    ob, s = r_runtime

    def exact(p, x):
        return in_R(Parameters(k_p=p.k_p, k_i=p.k_i, k_v=p.k_v, f_c=1), x) if p.f_c != 2 else in_R(p, x)

    assert_fails(ob, dataclasses.replace(s, exact=exact), "the exact x ∈ R")
