"""The hunting certificate (``hunting-cycle/v1``): a symmetric stick–slip cycle with static friction (beyond the paper).

With ``f_s > f_c`` (the paper's conclusion leaves stiction to future work) a stick ends at ``φ = f_s`` with ``σ > 0``;
the mass then slips forward, ``ẋ = Ax − f_c e₃`` (eq. xDot, ``v > 0``), so ``y = x − f_c e₂`` has ``ẏ = Ay`` from
``y0(σ) = (σ, Δ, 0)``, ``Δ = f_s − f_c``.  Write ``y(τ; σ) = e^{Aτ}y0(σ) = (σ₁, p₁, v)`` and ``X = [σ] × [τ]`` (the
file's box).  The proof (main verifier: ``_certify/hunting_proof.py``, ``hunting_cycle.py``) has these steps, each a
premise under the main verifier's name:

1. [box] Assumption 1, ``f_c > 0``, ``f_s > f_c``, ``0 < σ_lo < σ_hi`` and ``0 < τ_a < τ_lo < τ_hi``.
2. [krawczyk] ``K(X) = x̃ − C·F(x̃) + (I − C·J(X))(X − x̃)`` lies in the interior of ``X``, for ``F = (v, σ₁ + σ)``
   and ``J`` its Jacobian over ``X``: ``F`` has exactly one zero ``(σ*, τ*)`` in ``X``, and it lies in ``K(X)``.
3. [first_zero.*] ``τ*`` is the first zero of ``v`` for every ``σ`` of ``[σ]``: ``v(0) = 0`` and ``v' > 0`` on
   ``[0, δ]`` (start), ``v > 0`` on ``[δ, τ_a]`` (positive), ``∂v/∂τ < 0`` on ``[τ_a, τ_hi]`` (decreasing: ``v > v(τ*)
   = 0`` on ``[τ_a, τ*)``).  So the slip lasts ``τ*`` and ends at ``σ₁ = −σ*``.
4. [stick] ``−f_s < f_c + p₁ < f_s`` on ``X``: the mass sticks, keeps ``σ = −σ*`` and leaves at ``φ = −f_s``, the
   mirror image of the start; the model is odd (``x ↦ −x``), so the solution is periodic.
5. [cycle.*] each interval the file states holds its number over ``K(X)``: ``slip_time = τ*``, ``stick_time = (f_s +
   f_c + p₁)/σ*`` (``φ`` falls at the rate ``σ*``), ``period = 2(slip_time + stick_time)``, ``multiplier = −dσ₁/dσ``
   along ``v = 0`` (implicit functions: ``−(E₁₁ − (Ay)₁E₃₁/(Ay)₃)``), ``stable``: ``|multiplier| < 1`` (``false``:
   ``> 1``; ``null`` claims nothing).
6. [verdict] the file says ``"proved"``.

The start and the stick hold at every true zero (``v'(0) = Δ > 0``; with Assumption 1 ``V = yᵀPy`` of eq.
(lyapLikeP) falls as ``−2(k_v k_p − k_i)v²``, so ``p₁² < Δ²``); they are decided all the same, over the whole box.

Every decision is a certain comparison of arb balls (``e^{AT}`` for a ball ``T`` holds ``e^{Aτ}`` for each ``τ`` in
it); undecided is not proved.  The main verifier's format rules (key sets) are not checked.
"""

from __future__ import annotations

from fractions import Fraction

import flint

from ._core import Malformed, Verdict, _ints, _kept, ball, q

PREMISES = ("box", "krawczyk", "first_zero.start", "first_zero.positive", "first_zero.decreasing", "stick",
            "cycle.sigma", "cycle.slip_time", "cycle.stick_time", "cycle.period", "cycle.multiplier", "cycle.stable",
            "verdict")
CYCLE = ("sigma", "slip_time", "stick_time", "period", "multiplier")
MAX_PIECES = 4096  # balls one positivity search may evaluate (more is not proved)


def interval(lo: Fraction, hi: Fraction):
    """A ball that holds every point of ``[lo, hi]``."""
    return ball(lo).union(ball(hi))


def system(kp: Fraction, ki: Fraction, kv: Fraction):
    """``A`` of eq. (xDot) in ``x = (σ, φ, v)``: ``σ̇ = −k_i v``, ``φ̇ = σ − k_p v``, ``v̇ = φ − k_v v`` (arb)."""
    return flint.arb_mat([[0, 0, -ball(ki)], [1, 0, -ball(kp)], [0, 1, -ball(kv)]])


def flow(A, lo: Fraction, hi: Fraction):
    """A ball matrix that holds ``e^{Aτ}`` for every ``τ`` of ``[lo, hi]``."""
    return (A * interval(lo, hi)).exp()


def start(g, ta: Fraction) -> Fraction | None:
    """A ``δ = τ_a/2^j`` (``6 ≤ j < 66``) with ``g(0, δ) > 0``, or None (not shown)."""
    delta = ta / 64
    for _ in range(60):
        if g(Fraction(0), delta) > 0:
            return delta
        delta /= 2
    return None


def positive(g, lo: Fraction, hi: Fraction) -> bool:
    """``g(a, b) > 0`` (a ball) on pieces that cover ``[lo, hi]``, halving undecided ones, left to right.

    False when a ball is certainly ``≤ 0``, an undecided piece is narrower than ``2⁻⁴⁰(hi − lo)`` or after
    ``MAX_PIECES`` balls (undecided is not shown).
    """
    stack, used = [(lo, hi)], 0
    while stack:
        a, b = stack.pop()
        used += 1
        value = g(a, b)
        if value > 0:
            continue
        if value <= 0 or used >= MAX_PIECES or (b - a) * 2**40 < hi - lo:
            return False
        stack += [((a + b) / 2, b), (a, (a + b) / 2)]
    return True


def pair(value: object) -> tuple[Fraction, Fraction]:
    if not (isinstance(value, list) and len(value) == 2):
        raise Malformed(f"not an interval [lo, hi]: {value!r:.60}")
    return q(value[0]), q(value[1])


def check(data: dict) -> Verdict:
    """Decide a ``hunting-cycle/v1`` file (module docstring), at its ``precision_bits``."""
    p, b, bits = data.get("parameters"), data.get("box"), data.get("precision_bits")
    if data.get("claim") != "symmetric hunting cycle" or not isinstance(p, dict) or not isinstance(b, dict):
        raise Malformed("a hunting certificate needs the claim, parameters and box")
    if type(bits) is not int or not 53 <= bits <= 4096:
        raise Malformed(f"precision_bits must be an integer in [53, 4096]; got {bits!r:.40}")
    cycle = data.get("cycle")
    if cycle is not None and (not isinstance(cycle, dict) or type(cycle.get("stable")) not in (bool, type(None))):
        raise Malformed("cycle must be an object whose stable is true, false or null")
    gains = tuple(q(p.get(n)) for n in ("k_p", "k_i", "k_v", "f_c", "f_s"))
    (s_lo, s_hi), (t_lo, t_hi), ta = pair(b.get("sigma")), pair(b.get("tau")), q(b.get("monotone_from"))
    verdict = Verdict("hunting-cycle/v1")
    old, flint.ctx.prec = flint.ctx.prec, bits
    try:
        _decide(verdict, gains, (s_lo, s_hi), (t_lo, t_hi), ta, cycle)
    finally:
        flint.ctx.prec = old
    verdict.add("verdict", data.get("verdict") == "proved")  # step 6
    return verdict


def _decide(verdict: Verdict, gains, sigma, tau, ta: Fraction, cycle: dict | None) -> None:
    kp, ki, kv, fc, fs = gains
    (s_lo, s_hi), (t_lo, t_hi) = sigma, tau
    # step 1: the box's shape (a stick exit at φ = f_s needs σ > 0) and the model's gains
    shape = ki > 0 and kp > 0 and kv * kp > ki and fc > 0 and fs > fc and 0 < s_lo < s_hi and 0 < ta < t_lo < t_hi
    if not verdict.add("box", shape):
        return _undecided(verdict, cycle)
    A = system(kp, ki, kv)

    def state(S, E):
        """``(y, Ay)`` for ``y = E·y0(σ)``, ``σ ∈ S``."""
        y = E * flint.arb_mat([[S], [ball(fs - fc)], [0]])
        return y, A * y

    def jacobian(S, T):
        E = (A * T).exp()
        y, dy = state(S, E)
        return E, y, dy, flint.arb_mat([[E[2, 0], dy[2, 0]], [E[0, 0] + 1, dy[0, 0]]])

    # step 2: Krawczyk on the ball box S × T ⊇ X (its K inside int X ⊆ int(S × T)), at the exact centre x̃
    S, T = interval(s_lo, s_hi), interval(t_lo, t_hi)
    sm, tm = S.mid(), T.mid()
    _, ym, _, Jm = jacobian(sm, tm)
    _, yX, _, J = jacobian(S, T)
    try:
        C = flint.arb_mat([[x.mid() for x in row] for row in Jm.mid().inv().tolist()])  # any C will do
    except ZeroDivisionError:
        C = flint.arb_mat(2, 2)
    xm = flint.arb_mat([[sm], [tm]])
    K = xm - C * flint.arb_mat([[ym[2, 0]], [ym[0, 0] + sm]]) + (flint.arb_mat([[1, 0], [0, 1]]) - C * J) * (
        flint.arb_mat([[S], [T]]) - xm)
    inside = all(K[i, 0] > ball(lo) and K[i, 0] < ball(hi) for i, (lo, hi) in enumerate((sigma, tau)))
    zero = verdict.add("krawczyk", inside)

    # step 3: v > 0 on (0, τ*) for every σ of the box, so τ* is the first zero of v
    def slip(a: Fraction, b: Fraction):
        return state(S, flow(A, a, b))

    delta = start(lambda a, b: slip(a, b)[1][2, 0], ta)
    started = verdict.add("first_zero.start", delta is not None)
    if zero and started:  # the search runs only where the rest can still prove a cycle (the main verifier's order)
        verdict.add("first_zero.positive", delta is not None and _kept(("hunting", flint.ctx.prec, _ints(
            *gains, s_lo, s_hi, delta, ta)), lambda: positive(lambda a, b: slip(a, b)[0][2, 0], delta, ta)))
    verdict.add("first_zero.decreasing", slip(ta, t_hi)[1][2, 0] < 0)
    # step 4: the mass sticks at the end of the slip, φ₁ = f_c + p₁ in (−f_s, f_s), over X
    phi = ball(fc) + yX[1, 0]
    verdict.add("stick", phi > -ball(fs) and phi < ball(fs))

    # step 5: the file's numbers of the cycle, enclosed over K(X), which holds (σ*, τ*)
    if cycle is None or not zero:
        return _undecided(verdict, cycle)
    Sk, Tk = K[0, 0], K[1, 0]
    E, y, dy, _ = jacobian(Sk, Tk)
    stick = (ball(fs) + ball(fc) + y[1, 0]) / Sk
    multiplier = -(E[0, 0] - dy[0, 0] * E[2, 0] / dy[2, 0])
    values = {"sigma": Sk, "slip_time": Tk, "stick_time": stick, "period": 2 * (Tk + stick), "multiplier": multiplier}
    for name in CYCLE:
        lo, hi = pair(cycle.get(name))
        verdict.add(f"cycle.{name}", values[name] >= ball(lo) and values[name] <= ball(hi))
    shown = True if abs(multiplier) < 1 else False if abs(multiplier) > 1 else None
    verdict.add("cycle.stable", cycle.get("stable") in (None, shown))


def _undecided(verdict: Verdict, cycle: dict | None) -> None:
    """The numbers of a cycle not shown to exist are not shown either (as the main verifier has it)."""
    for name in (*CYCLE, "stable") if cycle is not None else ():
        verdict.add(f"cycle.{name}", None, "not decided: no zero is proved")
