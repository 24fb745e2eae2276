"""Parameters: exact storage, Assumption 1, physical constructor."""

import dataclasses
from fractions import Fraction

import pytest

from symbolic_friction import TABLE_I, Parameters
from symbolic_friction.errors import AssumptionError, InvalidNumberError, NonFiniteError


def test_exact_storage_and_c():
    p = Parameters(k_p=3, k_i=4, k_v="6.4", f_c=1)
    assert (p.k_p, p.k_i, p.k_v, p.f_c) == (3, 4, Fraction(32, 5), 1)
    assert p.c == 2 * (Fraction(32, 5) * 3 - 4)
    assert p.as_strings() == {"k_p": "3", "k_i": "4", "k_v": "32/5", "f_c": "1"}


def test_frozen():
    p = TABLE_I["a"]
    with pytest.raises(dataclasses.FrozenInstanceError):
        p.k_p = Fraction(1)  # type: ignore[misc]


def test_table_i():
    assert Parameters.table_i("b") == Parameters(k_v="1.5", k_p="0.66", k_i="0.08", f_c=1)
    with pytest.raises(AssumptionError, match="Table I has cases 'a' and 'b'; got 'c'"):
        Parameters.table_i("c")


def test_assumption1_message_gives_numbers():
    with pytest.raises(AssumptionError, match=r"Assumption 1 needs k_v·k_p > k_i; got 1 ≤ 3/2"):
        Parameters(k_p=1, k_i="1.5", k_v=1)


def test_assumption1_boundary_is_rejected():
    with pytest.raises(AssumptionError, match="k_v·k_p > k_i; got 4 ≤ 4"):
        Parameters(k_p=2, k_i=4, k_v=2)


@pytest.mark.parametrize(("field", "value"), [("k_i", 0), ("k_i", -1), ("k_p", 0), ("k_p", "-0.5")])
def test_positive_gains(field, value):
    kwargs = {"k_p": 3, "k_i": 4, "k_v": "6.4", field: value}
    with pytest.raises(AssumptionError, match=f"Assumption 1 needs {field} > 0; got {field} = "):
        Parameters(**kwargs)


@pytest.mark.parametrize("f_c", [0, "-1", Fraction(-1, 3)])
def test_fc_positive(f_c):
    with pytest.raises(AssumptionError, match="f_c > 0; got f_c = "):
        Parameters(k_p=3, k_i=4, k_v="6.4", f_c=f_c)


@pytest.mark.parametrize("bad", [float("nan"), float("inf"), "-inf"])
def test_non_finite_gain(bad):
    with pytest.raises(NonFiniteError, match="k_v must be finite"):
        Parameters(k_p=3, k_i=4, k_v=bad)


def test_non_numeric_gain():
    with pytest.raises(InvalidNumberError, match="k_p must be a decimal"):
        Parameters(k_p="three", k_i=4, k_v=7)


def test_from_physical():
    p = Parameters.from_physical(m=2, k_p_bar=6, k_i_bar=8, k_d_bar="12.3", alpha_v="0.5", f_c_bar=2)
    assert p == Parameters(k_p=3, k_i=4, k_v="6.4", f_c=1)


@pytest.mark.parametrize("m", [0, -1, "-0.1"])
def test_from_physical_mass(m):
    with pytest.raises(AssumptionError, match="the mass needs m > 0; got m = "):
        Parameters.from_physical(m=m, k_p_bar=6, k_i_bar=8, k_d_bar=12, f_c_bar=2)


def test_from_physical_alpha_v():
    with pytest.raises(AssumptionError, match="alpha_v ≥ 0; got alpha_v = -1"):
        Parameters.from_physical(m=1, k_p_bar=6, k_i_bar=8, k_d_bar=12, alpha_v=-1, f_c_bar=2)


def test_from_physical_non_finite():
    with pytest.raises(NonFiniteError, match="m must be finite"):
        Parameters.from_physical(m=float("nan"), k_p_bar=6, k_i_bar=8, k_d_bar=12, f_c_bar=2)


def test_from_physical_fc():
    with pytest.raises(AssumptionError, match="f_c_bar > 0; got f_c_bar = 0"):
        Parameters.from_physical(m=1, k_p_bar=6, k_i_bar=8, k_d_bar=12, f_c_bar=0)


def test_routh_margin():
    assert TABLE_I["a"].routh_margin == Fraction(32, 5) * 3 / 4


def test_static_level_defaults_to_coulomb_and_is_invisible_then():
    from fractions import Fraction

    p = Parameters(k_p=3, k_i=4, k_v="6.4", f_c=2)
    q = Parameters(k_p=3, k_i=4, k_v="6.4", f_c=2, f_s=2)
    assert p.f_s == Fraction(2) and p == q and hash(p) == hash(q)
    assert p.as_strings() == {"k_p": "3", "k_i": "4", "k_v": "32/5", "f_c": "2"} and str(p) == str(q)
    assert not p.stiction and p.rho == 0


def test_static_level_above_coulomb():
    from fractions import Fraction

    p = Parameters(k_p=3, k_i=4, k_v="6.4", f_c=1, f_s="1.2")
    assert p.f_s == Fraction(6, 5) and p.stiction and p.rho == Fraction(1, 5)
    assert p.as_strings()["f_s"] == "6/5" and "f_s=6/5" in str(p)
    assert p != Parameters.table_i("a") and hash(p) != hash(Parameters.table_i("a"))
    assert Parameters.from_physical(m=2, k_p_bar=6, k_i_bar=8, k_d_bar="12.8", f_c_bar=2, f_s_bar="2.4") == p


def test_static_level_below_coulomb_is_refused_with_the_numbers():
    with pytest.raises(AssumptionError, match=r"f_s ≥ f_c; got f_s = 9/10 < f_c = 1"):
        Parameters(k_p=3, k_i=4, k_v="6.4", f_c=1, f_s="0.9")


def test_from_physical_keeps_the_physical_values():
    from symbolic_friction._model.parameters import PhysicalParameters

    p = Parameters.from_physical(m="0.5", k_p_bar="1.5", k_i_bar=2, k_d_bar="3.1", alpha_v="0.1", f_c_bar="0.5", f_s_bar="0.6")
    assert p.physical == PhysicalParameters(m="1/2", k_p_bar="3/2", k_i_bar=2, k_d_bar="31/10", alpha_v="1/10",
                                            f_c_bar="1/2", f_s_bar="3/5")
    assert p.physical.as_dict() == {"m": Fraction(1, 2), "k_p_bar": Fraction(3, 2), "k_i_bar": 2,
                                    "k_d_bar": Fraction(31, 10), "alpha_v": Fraction(1, 10), "f_c_bar": Fraction(1, 2)}
    assert (p.k_p, p.k_i, p.k_v, p.f_c, p.f_s) == (3, 4, Fraction(32, 5), 1, Fraction(6, 5))
    # the same dynamics compare and hash alike, wherever the gains came from
    plain = Parameters(k_p=3, k_i=4, k_v="6.4", f_c=1, f_s="1.2")
    assert p == plain and hash(p) == hash(plain) and plain.physical is None


def test_physical_values_must_normalise_to_the_gains():
    import dataclasses

    p = Parameters.from_physical(m=2, k_p_bar=6, k_i_bar=8, k_d_bar="12.3", alpha_v="0.5", f_c_bar=2)
    with pytest.raises(AssumptionError, match="k_p = 5 but the physical values give 3"):
        dataclasses.replace(p, k_p=5)
    with pytest.raises(AssumptionError, match="physical must be a PhysicalParameters"):
        Parameters(k_p=3, k_i=4, k_v=7, physical={"m": 1})
    assert dataclasses.replace(p, f_s=2).physical is p.physical  # the static level is not a certified gain
