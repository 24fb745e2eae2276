"""Gain sets that the batch and kernel tests share: Table I, stiff, triple root and a creeping solution."""

from fractions import Fraction as F

from symbolic_friction import Parameters

GAIN_SETS = {
    "a": Parameters.table_i("a"),
    "b": Parameters.table_i("b"),
    "stiff": Parameters(k_v="51.1", k_p="5.3525", k_i="12.8775"),  # (s² + 0.1 s + 0.2525)(s + 51)
    "triple": Parameters(k_v=3, k_p=3, k_i=1),
    "creep": Parameters(k_v=17, k_p=336, k_i=1746, f_c=F(3828, 4096)),
}
