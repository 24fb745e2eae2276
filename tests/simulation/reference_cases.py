"""Regression cases of the high-precision reference (``symbolic_friction._reference``), as plain data.

Each case is ``(params, z0, t_end)`` in :data:`CASES`; :data:`EXPECTED` holds
what the reference computed for it: the events ``(t, mode_before, mode_after)``
and the state ``z(T) = (e_i, s, v)``, as decimal strings of 25 significant
digits, so that tests can compare without running mpmath.  The values were
computed at ``dps = 60`` and agree with ``dps = 40`` to the digits written
(see ``test_reference.py``).

* ``creep``: a slip leaves a stick at ``φ = -f_c`` and creeps (``v`` small,
  ``φ`` just past ``-f_c``) to the horizon, ``φ`` falling at ``σ ≈ -0.1185``;
* ``stiff_stall``: ``k_v = 1001``, margin ``1.001``: slip(-1), slip(+1), stick
  on ``[1.465899…, 1.736015…]``, slip(-1) to the horizon (the same times come
  out of ``scipy.linalg.expm`` with ``brentq`` in double precision);
* ``stiff_cost``: ``k_v = 71929``, fast mode ``≈ -k_v``, slow pair with
  period ``≈ 65 > T``: one slip, no event;
* ``kv2e5``, ``kv1e8``: ``k_v ≈ 2·10⁵`` and ``10⁸``;
* ``stiction``: ``f_c = 2``, ``f_s = 6/5 f_c``, ``k_v = 1000``.

:func:`random_case` draws the stiff admissible gain sets the reference must
handle (log-uniform ``k_p, k_i`` in ``[10⁻⁴, 10⁴]``, Routh margin
``m = k_v k_p/k_i = 1 + 10^U``, ``U`` uniform in ``[-4, 1]``, ``|z0|``
log-uniform in ``[0.1, 100]``, ``T = 20``).
"""

from __future__ import annotations

import math
import random
from fractions import Fraction as F

from symbolic_friction import Parameters

T_END = 20.0

CASES = {
    "creep": (
        Parameters(k_p=F(1060, 801701), k_i=F(22712, 691263), k_v=F(4172116181768452, 166254215934015)),
        (6.8051, 3.8260, -5.6357),
        T_END,
    ),
    "stiff_stall": (Parameters(k_p=F(1, 1000), k_i=F(1), k_v=F(1001)), (-11.81, 7.38, -10.99), T_END),
    "stiff_cost": (Parameters(k_p=F(23, 2500), k_i=F(660), k_v=F(71929)), (-6.0, -6.0, 6.0), T_END),
    "kv2e5": (Parameters(k_p=F(1, 100), k_i=F(2000), k_v=F(200200)), (3.0, -2.0, 1.0), T_END),
    "kv1e8": (Parameters(k_p=F(1, 10000), k_i=F(5000), k_v=F(10**8)), (3.0, -2.0, 1.0), T_END),
    "stiction": (Parameters(k_p=F(1, 10), k_i=F(10), k_v=F(1000), f_c=F(2), f_s=F(12, 5)), (3.0, -2.0, 1.0), T_END),
}

# EXPECTED-BEGIN (written by the reference at dps = 60)
EXPECTED = {
    'creep': {
        "events": [
            ('0.2089340771616202736239358', -1, 0),
            ('6.507587266062282126056432', 0, -1),
        ],
        "z_end": ('77.07394503760362905938543', '3.188703866138439133597228', '-0.06106314954196076949925869'),
        "status": 't_end',
    },
    'stiff_stall': {
        "events": [
            ('0.006753818565486346873260884', -1, 1),
            ('1.465899114218802011923031', 1, 0),
            ('1.736015223710303157767798', 0, -1),
        ],
        "z_end": ('128.3668099054529154316533', '6.181678496422670273614463', '-0.127239576504578309872444'),
        "status": 't_end',
    },
    'stiff_cost': {
        "events": [
        ],
        "z_end": ('-56.91815237547796102265271', '2.56990377782235939283306', '0.5222508377067019706416567'),
        "status": 't_end',
    },
    'kv2e5': {
        "events": [
            ('1.766701837440223605993017e-5', 1, -1),
            ('1.488669681667638371362363', -1, 0),
            ('1.489159163329654304368388', 0, 1),
        ],
        "z_end": ('-19.44958636275579531403669', '0.5576457906226857600839786', '0.1942965670326708956258488'),
        "status": 't_end',
    },
    'kv1e8': {
        "events": [
            ('8.80495866353413581174792e-8', 1, -1),
            ('1.499843762544896889254696', -1, 0),
            ('1.50004374129834584702026', 0, 1),
        ],
        "z_end": ('-36.89675119125772295590358', '-1.983023480805501000911338', '0.001844827560554397888207154'),
        "status": 't_end',
    },
    'stiction': {
        "events": [
            ('0.003481171875945023069730557', 1, -1),
            ('1.382741954912052693659599', -1, 0),
            ('1.599752563570921820868624', 0, 1),
        ],
        "z_end": ('-19.63410230620006933296009', '0.5391689733601467757937681', '0.1942925153412113118936471'),
        "status": 't_end',
    },
}
# EXPECTED-END


def _round(x: float, digits: int) -> F:
    """``x`` rounded to ``digits`` significant decimal digits, as an exact Fraction."""
    return F(f"{x:.{digits - 1}e}")


def random_case(seed: int, *, digits: int = 3, friction: bool = True, log_margin: tuple[float, float] = (-4.0, 1.0)):
    """A random stiff admissible case ``(params, z0, t_end)`` from ``seed``.

    Parameters
    ----------
    seed : int
    digits : int
        Significant digits ``k_p``, ``k_i`` and ``m - 1`` are rounded to.
    friction : bool
        With ``False`` always ``f_c = 1 = f_s``; with ``True`` one case in four
        has ``f_c`` log-uniform in ``[0.5, 2]`` and one in four ``f_s > f_c``.
    log_margin : (float, float)
        The range of ``U`` below (``(-9, -4)``: the Routh boundary's neighbourhood).

    Returns
    -------
    params : Parameters
        ``k_p, k_i`` log-uniform in ``[10⁻⁴, 10⁴]``; ``k_v = m k_i/k_p`` exactly,
        with ``m = 1 + 10^U`` rounded, ``U`` uniform in ``log_margin``, so the
        Routh margin of Assumption 1 is exactly ``m > 1``.
    z0 : tuple of 3 floats
        ``|z0|`` log-uniform in ``[0.1, 100]``, direction uniform on the sphere.
    t_end : float
        ``20``.
    """
    rng = random.Random(seed)
    k_p = _round(10 ** rng.uniform(-4, 4), digits)
    k_i = _round(10 ** rng.uniform(-4, 4), digits)
    margin = 1 + _round(10 ** rng.uniform(*log_margin), digits)
    k_v = margin * k_i / k_p
    f_c, f_s = F(1), None
    if friction:
        if rng.random() < 0.25:
            f_c = _round(10 ** rng.uniform(math.log10(0.5), math.log10(2)), digits)
        if rng.random() < 0.25:
            f_s = f_c * (1 + _round(rng.uniform(0.05, 0.5), 2))
    while True:
        d = [rng.gauss(0, 1) for _ in range(3)]
        n = math.sqrt(sum(c * c for c in d))
        if n > 1e-3:
            break
    r = 10 ** rng.uniform(-1, 2)
    z0 = tuple(r * c / n for c in d)
    return Parameters(k_p=k_p, k_i=k_i, k_v=k_v, f_c=f_c, f_s=f_s), z0, T_END
