"""Single-point mutants of the runtime model, the verifier, the k-conditions and the cross-check.

Each mutant replaces one snippet (which must occur exactly once in its
file) by a wrong version.  ``python tests/mutation/run.py`` applies each to
a copy of the package and runs ``symbolic-friction check`` and
``symbolic-friction verify`` on it: every mutant must be caught by one of
them, or be listed as *equivalent* with a one-line proof that it cannot
change any result.
"""

from __future__ import annotations

from dataclasses import dataclass, replace

__all__ = ["Mutant", "MUTANTS", "FAST"]

TARGETS = ("model", "verifier", "k-conditions", "cross-check", "kernel", "modes", "hunting", "obligations")


@dataclass(frozen=True)
class Mutant:
    """One single-point change: ``old`` → ``new`` in ``path`` (relative to the repository root)."""

    id: str
    target: str
    path: str
    old: str
    new: str
    description: str
    equivalent: str | None = None
    tests: tuple[str, ...] = ()
    """Test ids (``file::name``) run on the mutated copy when ``check`` and ``verify`` miss it."""


_L = "symbolic_friction/_model/lyapunov.py"
_A = "symbolic_friction/_model/attractor.py"
_C = "symbolic_friction/_model/coordinates.py"
_K = "symbolic_friction/_model/kinds.py"
_M = "symbolic_friction/_simulation/modes.py"
_S = "symbolic_friction/_simulation/search.py"
_KC = "symbolic_friction/_model/kconditions.py"
_V = "symbolic_friction/_certify/verify.py"
_CE = "symbolic_friction/_certify/certificate.py"
_T = "symbolic_friction/_crosscheck/_results.py"
_L2 = "symbolic_friction/_crosscheck/lemma2.py"
_P1 = "symbolic_friction/_crosscheck/prop1.py"
_AL = "symbolic_friction/_crosscheck/_along.py"
_PR = "symbolic_friction/_crosscheck/_property.py"
_R = "symbolic_friction/_crosscheck/_run.py"
_SI = "symbolic_friction/_simulation/_trajectories.py"
_RC = "symbolic_friction/_certify/reset_contraction_proof.py"
_KER = "symbolic_friction/_simulation/_kernel.py"
_KF = "symbolic_friction/_simulation/_kernel_flow.py"
_HP = "symbolic_friction/_certify/hunting_proof.py"
_HM = "symbolic_friction/_hunting/_map.py"
_MT = "symbolic_friction/_crosscheck/mode_table.py"
_OB = "symbolic_friction/_obligations/_base.py"
_OI = "symbolic_friction/_obligations/__init__.py"

MUTANTS: tuple[Mutant, ...] = (
    # ------------------------------------------------------------------ the runtime model
    Mutant("V.at_rest", "model", _L, "kind.where(v < 0, -f_c, sat(phi, f_c))", "kind.where(v < 0, -f_c, 0 * phi)",
           "V at v = 0 uses f = 0 instead of the minimiser sat(φ)"),
    Mutant("V.slip_sign", "model", _L, "return kind.where(v > 0, f_c, kind.where(", "return kind.where(v > 0, -f_c, kind.where(",
           "V for v > 0 uses f = -f_c"),
    Mutant("quadratic_form.half", "model", _L, "if P[i][j] != 0)", "if P[i][j] != 0 and i <= j)",
           "the quadratic form drops the symmetric half of the σv cross term"),
    Mutant("P.swapped_gains", "model", _L, "return ((k_v / k_i, 0, -1), (0, 1, 0), (-1, 0, k_p))",
           "return ((k_p / k_i, 0, -1), (0, 1, 0), (-1, 0, k_v))", "P with k_p and k_v swapped"),
    Mutant("P.cross_sign", "model", _L, "return ((k_v / k_i, 0, -1), (0, 1, 0), (-1, 0, k_p))",
           "return ((k_v / k_i, 0, 1), (0, 1, 0), (1, 0, k_p))", "P with the sign of the σv entries flipped"),
    Mutant("V_k.stick_piece", "model", _L, "return quadratic_form(params, sigma, phi * 0, v * 0)",
           "return quadratic_form(params, sigma, phi * 0, v)", "V_0 keeps the v terms"),
    Mutant("V_k.slip_piece", "model", _L, "return quadratic_form(params, sigma, phi - f_c, v)",
           "return quadratic_form(params, sigma, phi + f_c, v)", "V_1 uses φ + f_c"),
    Mutant("Vhat.cross_term", "model", _L, "+ k3 * kind.abs(sigma) * kind.abs(v) + k4 * v**2 / 2",
           "+ 2 * k3 * kind.abs(sigma) * kind.abs(v) + k4 * v**2 / 2", "V̂'s k₃|σ||v| term doubled"),
    Mutant("Vhat.dz_term", "model", _L, "value = k1 * sigma**2 / 2 + k2 * d**2 / 2", "value = k1 * sigma**2 / 2 + k2 * phi**2 / 2",
           "V̂ uses φ² instead of dz(φ)²"),
    Mutant("Vhat.half_k4", "model", _L, "+ k4 * v**2 / 2\n", "+ k4 * v**2\n", "V̂'s ½k₄v² without the ½"),
    Mutant("R.strict", "model", _L, "return R_margin(params, x) >= 0", "return R_margin(params, x) > 0", "x ∈ R made strict"),
    Mutant("R.sign", "model", _L, "return v * (phi - kind.sign(v) * kind.scalar(params.f_c))",
           "return v * (phi + kind.sign(v) * kind.scalar(params.f_c))", "R with the sign of f_c flipped"),
    Mutant("hatV_rate.clarke", "model", _L, "abs_rate = kind.where(kind.abs(sigma) > 0, kind.sign(sigma) * f[0], kind.abs(f[0]))",
           "abs_rate = kind.sign(sigma) * f[0]", "V̂° without the Clarke max at σ = 0"),
    Mutant("hatV_rate.flow", "model", _L, "- b[i] * sv for i in range(3)]", "+ b[i] * sv for i in range(3)]",
           "V̂° along Ax + b sign(v) instead of Ax − b sign(v)"),
    Mutant("dz.bound", "model", _A, "    return kind.finish(y - sat(y, c))", "    return kind.finish(y - sat(y, 2 * c))",
           "dz_c with the dead zone [-2c, 2c]"),
    Mutant("dist_x.no_v", "model", _A, "    return sigma**2 + v**2 + dz(phi, attractor_bound_x(params)) ** 2",
           "    return sigma**2 + dz(phi, attractor_bound_x(params)) ** 2", "|x|²_𝒜 without v²"),
    Mutant("dist_z.bound", "model", _A, "dz(e_i, attractor_bound_z(params))", "dz(e_i, params.f_c)",
           "|z|²_𝒜 with dead zone f_c instead of f_c/k_i"),
    Mutant("attractor.bound_z", "model", _A, "return params.f_c / params.k_i", "return params.f_c / params.k_p",
           "𝒜 in z bounded by f_c/k_p"),
    Mutant("A.swapped", "model", _C, "return ((0, 0, -k_i), (1, 0, -k_p), (0, 1, -k_v))",
           "return ((0, 0, -k_i), (1, 0, -k_v), (0, 1, -k_p))", "A with k_p and k_v swapped"),
    Mutant("T_inv.sign", "model", _C, "return ((k_p / k_i**2, -1 / k_i, 0), (-1 / k_i, 0, 0), (0, 0, 1))",
           "return ((k_p / k_i**2, 1 / k_i, 0), (-1 / k_i, 0, 0), (0, 0, 1))", "T⁻¹ with one sign flipped"),
    Mutant("T.sign", "model", _C, "return ((0, -k_i, 0), (-k_i, -k_p, 0), (0, 0, 1))",
           "return ((0, -k_i, 0), (-k_i, k_p, 0), (0, 0, 1))", "T with φ = −k_i e_i + k_p s"),
    Mutant("b.scale", "model", _C, "    return (0, 0, f_c)", "    return (0, 0, 2 * f_c)", "b = (0, 0, 2f_c)"),
    Mutant("A.float_args", "model", _C, "    return np.array(system_matrix_entries(k_p, k_i, k_v), dtype=float)",
           "    return np.array(system_matrix_entries(k_p, k_v, k_i), dtype=float)", "the float A built with k_i, k_v swapped"),
    Mutant("kinds.float_clip", "model", _K, "        return np.clip(y, lo, hi)", "        return np.clip(y, lo, 2 * hi)",
           "the float projection on [lo, 2hi]"),
    Mutant("kinds.exact_sign", "model", _K, "        return (y > 0) - (y < 0)", "        return (y > 0) - (y <= 0)",
           "the exact sign(0) = -1"),
    Mutant("kinds.exact_clip_boundary", "model", _K, "        return lo if y < lo else hi if y > hi else y",
           "        return lo if y <= lo else hi if y > hi else y", "the exact projection tests y ≤ lo",
           equivalent="at y = lo both versions return lo (= y): the value is the same for every y"),
    Mutant("kinds.float_sign_zero", "model", _K, "        return np.sign(y)", "        return np.sign(y) * (y != 0)",
           "the float sign multiplied by [y ≠ 0]", equivalent="np.sign(0) = 0 already, so the factor changes no value"),
    Mutant("modes.at_rest", "model", _M, "return -1, 0.0 * offset - excess, -1 if sigma < 0 else 0  # rows (vii), (viii), (ix)",
           "return -1, 0.0 * offset - excess, -1 if sigma <= 0 else 0  # rows (vii), (viii), (ix)", "mode_at_rest sends row (viii) to slip"),
    Mutant("modes.table_row", "model", _M, 'return "iii" if sigma > 0 else "iv" if sigma == 0 else "v"',
           'return "iii" if sigma >= 0 else "iv" if sigma == 0 else "v"', "table_row puts σ = 0 in row (iii)"),
    Mutant("kernel.after_slip_clamp", "model", _KER, "    if direction * offset > 0.0:", "    if direction * offset < 0.0:",
           "the simulator's end-of-slip rule clamps the reachable side of the boundary"),
    Mutant("search.p_norm", "model", _KF, "return m * math.sqrt(max(kv_ki * s * s - 2.0 * s * v + k_p * v * v + p * p, 0.0))",
           "return m * math.sqrt(max(kv_ki * s * s + 2.0 * s * v + k_p * v * v + p * p, 0.0))",
           "the root search's |y|_P with +2σv (its bracket bound would be wrong)"),
    Mutant("search.p_weights", "model", _S, "    return P[0][0], P[2][2]", "    return P[2][2], P[0][0]",
           "the root search reads P₁₁ and P₃₃ swapped"),
    # ------------------------------------------------------------------ the k-conditions
    Mutant("kcond.k3_k2", "k-conditions", _KC, "        (k3, k2),", "        (k3, k2 / 2),", "k₃ > k₂ weakened to k₃ > k₂/2"),
    Mutant("kcond.k3_k1", "k-conditions", _KC, "        (k3, k_i * k1 / k_v),", "        (k3, k_v * k1 / k_i),",
           "k₃ > (k_i/k_v)k₁ with k_i and k_v swapped"),
    Mutant("kcond.k4_k2", "k-conditions", _KC, "        (k4, k_p * k2),", "        (k4, k2),", "k₄ > k_p k₂ without k_p"),
    Mutant("kcond.k4_k3", "k-conditions", _KC, "        (k4, k_i * k3 / k_v),", "        (k4, k_i * k3 / k_v / 2),",
           "k₄ > (k_i/k_v)k₃ halved"),
    Mutant("kcond.definiteness", "k-conditions", _KC, "        (k1 * k4, k3**2),", "        (k1 * k4, k3),",
           "k₁k₄ > k₃² with k₃ unsquared"),
    Mutant("kcond.holds_strict", "k-conditions", _KC, "        return sides[0] > sides[1]", "        return sides[0] >= sides[1]",
           "Condition.holds made non-strict"),
    # ------------------------------------------------------------------ the verifier
    Mutant("verify.drop_c2", "verifier", _V,
           '    out.append(Semidefinite("lemma3.R", "c2·I − P ⪰ 0", _matrix(cert.c2 * identity[i][j] - p[i][j] for i in range(3) for j in range(3))))\n',
           "", "c₂I − P ⪰ 0 dropped (a c₂ below λ_max(P) would verify)"),
    Mutant("verify.drop_c1hat_k4", "verifier", _V, "for j, kj in ((1, cert.k1), (2, cert.k2), (4, cert.k4)):",
           "for j, kj in ((1, cert.k1), (2, cert.k2)):", "ĉ₁ ≤ k₄/2 dropped"),
    Mutant("verify.leading_minors", "verifier", _V, "            for idx in itertools.combinations(range(n), size)\n        ]",
           "            for idx in [tuple(range(size))]\n        ]", "semidefiniteness by leading principal minors only"),
    Mutant("verify.kappa_hat_factor", "verifier", _CE, "    return (c2 * c2_hat) / (c1 * c1_hat)", "    return c2 / c1",
           "κ² without the hat factor ĉ₂/ĉ₁"),
    Mutant("verify.strict_decision", "verifier", _V, '_DECIDE = {">": lambda m: m > 0,', '_DECIDE = {">": lambda m: m >= 0,',
           "strict inequalities decided as non-strict"),
    Mutant("verify.c_formula", "verifier", _V, 'cert.c, "==", 2 * (k_v * k_p - k_i)', 'cert.c, "==", (k_v * k_p - k_i)',
           "c = k_v k_p − k_i (the factor 2 dropped)"),
    Mutant("verify.drop_c1_positive", "verifier", _V, '        Inequality("lemma2.lower_bound", "c1 > 0", cert.c1, ">", zero),\n', "",
           "c₁ > 0 dropped"),
    Mutant("verify.kappa_reversed", "verifier", _V, '            kappa * kappa,\n            ">=",', '            kappa * kappa,\n            "<=",',
           "κ² compared the wrong way"),
    Mutant("verify.le_margin", "verifier", _V, '            return self.rhs - self.lhs, ">="', '            return self.lhs - self.rhs, ">="',
           "every ≤ premise decided reversed"),
    Mutant("verify.psd_some_minors", "verifier", _V, "negative = [(idx, d) for idx, d in minors if not d >= 0]",
           "negative = [(idx, d) for idx, d in minors[:3] if not d >= 0]", "the PSD decision looks at the 1×1 minors only"),
    Mutant("verify.drop_kappa_positive", "verifier", _V,
           '        Inequality("prop1.stability_bound", "overshoot_bound > 0", kappa, ">", zero),\n', "", "κ > 0 dropped"),
    Mutant("verify.drop_assumption1", "verifier", _V, '        Inequality("lemma2.P", "k_v·k_p > k_i", k_v * k_p, ">", k_i),\n', "",
           "Assumption 1's k_v k_p > k_i dropped"),
    Mutant("verify.c1_halved", "verifier", _V, "_matrix(p[i][j] - cert.c1 * identity[i][j]",
           "_matrix(p[i][j] - cert.c1 * identity[i][j] / 2", "P − c₁I ⪰ 0 weakened to P − (c₁/2)I ⪰ 0"),
    # ------------------------------------------------------------------ the cross-check
    Mutant("cc.acc_never_fails", "cross-check", _T, "self.failures += int(np.count_nonzero(r < -self.rtol))",
           "self.failures += int(np.count_nonzero(r < -np.inf))", "no property can record a failure"),
    Mutant("cc.decrease_without_c", "cross-check", _L2, "return _pair_evaluation(self.id, a, certificate.c, _scale(a, certificate))",
           "return _pair_evaluation(self.id, a, 0.0, _scale(a, certificate))", "Lemma 2's decrease checked without c∫v²"),
    Mutant("cc.lower_bound_half", "cross-check", _L2, "rel = (a.V - c1 * a.d2) / _scale(a, certificate)",
           "rel = (a.V - 0.5 * c1 * a.d2) / _scale(a, certificate)", "Lemma 2's lower bound checked with c₁/2"),
    Mutant("cc.stability_kappa", "cross-check", _P1, "rel = (kappa * a.d0[:, None] - a.d) / a.L[:, None]",
           "rel = (2 * kappa * a.d0[:, None] - a.d) / a.L[:, None]", "Proposition 1's bound checked with 2κ"),
    Mutant("cc.rhat_flipped", "cross-check", _AL, "return self.valid & self.is_sample & ~in_R(",
           "return self.valid & self.is_sample & in_R(", "R̂ and R swapped in the cross-check"),
    Mutant("cc.tolerance", "cross-check", _PR, "DEFAULT_RTOL = 1e-8", "DEFAULT_RTOL = 1e3", "tolerance made huge"),
    Mutant("cc.accepts_unproved", "cross-check", _R, "            if not report.proved:", "            if False:",
           "unproved certificates are cross-checked instead of refused"),
    Mutant("cc.hides_event_limit", "cross-check", _SI, "    COMPLETE = (T_END, EQUILIBRIUM, FALLBACK)",
           "    COMPLETE = (T_END, EQUILIBRIUM, FALLBACK, MAX_EVENTS)", "trajectories that hit the event limit count as complete"),
)

NEW: tuple[Mutant, ...] = (
    # ------------------------------------------------------------------ the event kernel
    Mutant("ker.emit_stick_fc", "kernel", _KER, "x0, x1, x2 = sigma, base * f_c + (offset + sigma * tau), 0.0",
           "x0, x1, x2 = sigma, base + (offset + sigma * tau), 0.0", "a stick's dense output without the factor f_c in φ"),
    Mutant("ker.emit_slip_fc", "kernel", _KER, "x0, x1, x2 = ys, yp + mode * f_c, mode * max(mode * yv, 0.0)",
           "x0, x1, x2 = ys, yp + mode, mode * max(mode * yv, 0.0)", "a slip's dense output without the factor f_c in φ"),
    Mutant("ker.emit_v_sign", "kernel", _KER, "x0, x1, x2 = ys, yp + mode * f_c, mode * max(mode * yv, 0.0)",
           "x0, x1, x2 = ys, yp + mode * f_c, max(mode * yv, 0.0)", "a slip's dense output gives |v| for v < 0"),
    Mutant("ker.step_e01_index", "kernel", _KER, "e01 = w1 * K[b1 + 1] + w0 * K[b2 + 1]",
           "e01 = w1 * K[b1 + 2] + w0 * K[b2 + 1]", "index slip in the stepped propagator (uniform grids only)"),
    Mutant("ker.step_e22_index", "kernel", _KER, "e22 = w2 + w1 * K[b1 + 8] + w0 * K[b2 + 8]",
           "e22 = w2 + w1 * K[b1 + 8] + w0 * K[b2 + 7]", "index slip in the stepped propagator's last entry",
           equivalent="B2's entries (3,2) and (3,3) are both 0 for every gain set (B2 = [[k_p, −k_i, 0], [k_v, 0, −k_i], [1, 0, 0]]), so K[b2+7] = K[b2+8]"),
    Mutant("ker.step_w_swap", "kernel", _KER, "e11 = w2 + w1 * K[b1 + 4] + w0 * K[b2 + 4]",
           "e11 = w1 + w1 * K[b1 + 4] + w0 * K[b2 + 4]", "the stepped propagator's diagonal with w' for w''"),
    Mutant("ker.step_rows", "kernel", _KER, "e10 * ys + e11 * yp + e12 * yv,", "e10 * ys + e11 * yp + e21 * yv,",
           "the stepped propagator applied with e₂₁ for e₁₂"),
    # the reset-contraction certificate's verifier (check's self-check: its false certificates)
    Mutant("rc.rho_abs_dropped", "verifier", _RC, "bool(abs(e11) <= rho)", "bool(e11 <= rho)",
           "|E₁₁| ≤ ρ decided without the absolute value (E₁₁ < 0 in case (a): any ρ passes)",
           tests=("tests/certify/test_reset_contraction.py",)),
    Mutant("rc.rho_one_allowed", "verifier", _RC, '_exact("rho < 1", cert.rho, "<", Fraction(1))',
           '_exact("rho < 1", cert.rho, "<=", Fraction(1))', "ρ = 1 accepted (no contraction)",
           tests=("tests/certify/test_reset_contraction.py",)),
    Mutant("rc.dwell_term_dropped", "verifier", _RC, "bound = radius * (abs(e21) + rho * q(wait))",
           "bound = radius * abs(e21)", "the radius premise without the dwell's wait",
           tests=("tests/certify/test_reset_contraction.py",)),
    Mutant("rc.settling_tol_doubled", "verifier", _RC, "value <= cert.tol)", "value <= 2 * cert.tol)",
           "ρ^cycles compared with 2·tol", tests=("tests/certify/test_reset_contraction.py",)),
    # reset PID (check's reset.kernel_binding sees a kernel that resets elsewhere or to elsewhere)
    Mutant("ker.reset_to_wrong_side", "kernel", _KER, "base, offset = d, 0.0", "base, offset = -d, 0.0",
           "a reset puts φ at -sign(σ) f_c (the stick goes on instead of ending)"),
    Mutant("ker.reset_only_pushing_away", "kernel", _KER, "if d * phi_now < f_c:", "if d * phi_now <= 0.0:",
           "the reset only where σφ ≤ 0 (not while φ is short of sign(σ) f_c on σ's side)"),
    Mutant("ker.reset_ignores_dwell", "kernel", _KER, "t_allow = t if n_resets == 0 else max(t, t_reset + dwell)",
           "t_allow = t", "resets without the dwell timer",
           tests=("tests/simulation/test_reset.py::test_the_dwell_time_separates_resets",)),
    Mutant("ker.reset_past_the_ramp", "kernel", _KER, "if t_allow < t_cross and t_allow < t_end:",
           "if t_allow < t_end:", "a reset also after φ would have reached sign(σ) f_c by itself",
           tests=("tests/simulation/test_reset.py::test_reset_trajectories_match_the_reference",)),
    Mutant("ker.stick_gap_fc", "kernel", _KER, "gap = -offset if base == d else (d - base) * f_c - offset",
           "gap = -offset if base == d else (d - base) - offset", "the stick duration without the factor f_c"),
    Mutant("ker.stick_gap_sign", "kernel", _KER, "gap = -offset if base == d else (d - base) * f_c - offset",
           "gap = -offset if base == d else (d - base) * f_c + offset", "the stick duration with +offset"),
    Mutant("ker.stiction_exit_sign", "kernel", _KER, "gap += d * excess", "gap -= d * excess",
           "the stick ends at ±(2f_c − f_s) instead of ±f_s (sign slip in the stiction exit)"),
    Mutant("ker.stiction_exit_dropped", "kernel", _KER, "                if excess != 0.0:\n                    gap += d * excess\n",
           "", "the stick ends at ±f_c with f_s > f_c"),
    Mutant("ker.slip_offset_sign", "kernel", _KER, "(d * excess if excess != 0.0 else 0.0)", "(-d * excess if excess != 0.0 else 0.0)",
           "the slip after a stick starts from φ = d(2f_c − f_s) (sign slip in the slip offset)"),
    Mutant("ker.slip_offset_dropped", "kernel", _KER, "(d * excess if excess != 0.0 else 0.0)", "(0.0 if excess != 0.0 else 0.0)",
           "the slip after a stick starts without the jump f_s − f_c in v'"),
    Mutant("ker.event_phi_fc", "kernel", _KER, "ev_x[n_ev, 1] = base * f_c + offset", "ev_x[n_ev, 1] = base + offset",
           "the event state φ at the end of a slip without the factor f_c"),
    Mutant("ker.stick_event_phi", "kernel", _KER, "ev_x[n_ev, 1] = d * f_s", "ev_x[n_ev, 1] = d * f_c",
           "the event state φ at a stick exit is ±f_c, not ±f_s"),
    Mutant("ker.slip_start_fc", "kernel", _KER, "(offset if base == d else (base - d) * f_c + offset)",
           "(offset if base == d else (base - d) + offset)", "a slip's start offset without the factor f_c"),
    Mutant("ker.slip_start_sign", "kernel", _KER, "(offset if base == d else (base - d) * f_c + offset)",
           "(offset if base == d else (d - base) * f_c + offset)", "a slip's start offset with (d − base) f_c"),
    Mutant("ker.rest_ignores_stiction", "kernel", _KER, "base, offset, mode = mode_at_rest(sigma, 0, phi, f_c, tol, excess)",
           "base, offset, mode = mode_at_rest(sigma, 0, phi, f_c, tol)", "an initial state at rest is classified with f_s = f_c"),
    Mutant("ker.after_slip_ignores_stiction", "kernel", _KER, "base, offset, new_mode = mode_after_slip(ys, yp, d, f_c, tol, excess)",
           "base, offset, new_mode = mode_after_slip(ys, yp, d, f_c, tol)", "the end of a slip is classified with f_s = f_c"),
    Mutant("ker.stick_slip_cache_strict", "kernel", _KER, "found = FOUND if tau <= horizon else NONE",
           "found = FOUND if tau < horizon else NONE", "a cached stick-slip ending exactly at the horizon is not an event",
           equivalent="τ = horizon exactly: FOUND then emits up to t_end and stops at t ≥ t_end; NONE emits up to t_end, the same samples, and the event at t_end is past the horizon"),
    Mutant("ker.final_sample_strict", "kernel", _KER, "while i < m and (ts[i] < t1 or (final and ts[i] <= t1)):",
           "while i < m and (ts[i] < t1 or (final and ts[i] < t1)):", "the last sample at t_end is never written"),
    Mutant("ker.stick_exit_direction", "kernel", _KER, "d = 1 if sigma > 0.0 else -1\n                if dwell >= 0.0:",
           "d = 1 if sigma >= 0.0 else -1\n                if dwell >= 0.0:", "a stick with σ > 0 … (σ ≥ 0: same, σ = 0 returns before)",
           equivalent="σ = 0 returns as an equilibrium two lines above, so σ ≥ 0 and σ > 0 agree wherever this line runs"),
    # ------------------------------------------------------------------ the closed form and the search
    Mutant("kf.scan_skips_last_partial_cell", "kernel", _KF,
           "    r_p = p_norm(s, p, v, kv_ki, k_p)\n    last = min(n_cells, int(math.ceil((horizon - a_w) / dt)))",
           "    r_p = p_norm(s, p, v, kv_ki, k_p)\n    last = min(n_cells, int((horizon - a_w) / dt))",
           "the scan skips the last partial cell before the horizon"),
    Mutant("kf.scan_cells_one_short", "kernel", _KF, "    for j in range(last):\n        u_next", "    for j in range(last - 1):\n        u_next",
           "the scan never looks at the last cell of a window"),
    Mutant("kf.scan_clears_on_one_end", "kernel", _KF, "if not min(u_prev, u_next) > slack + noise:",
           "if not max(u_prev, u_next) > slack + noise:", "a cell is cleared when one end (not both) is above the bound"),
    Mutant("kf.w2_sign", "kernel", _KF, "w2 = r * w1 + alpha * D + C", "w2 = r * w1 + alpha * D - C", "w'' with −C"),
    Mutant("kf.pair_cd_omega", "kernel", _KF, "return ea * math.cos(omega * t), ea * math.sin(omega * t) / omega",
           "return ea * math.cos(omega * t), ea * math.sin(omega * t)", "the oscillatory pair's D without 1/ω"),
    Mutant("kf.window_not_reanchored", "kernel", _KF, "        if a_w < horizon:\n            s, p, v = flow(K, q, a_w)\n", "",
           "the scan's next window starts from the offset at τ = 0"),
    Mutant("kf.march_not_fresh", "kernel", _KF, "    fresh = a == 0.0\n", "    fresh = False\n",
           "the march takes the slip's own start (u = 0) for its end"),
    Mutant("kf.newton_bracket", "kernel", _KF, "        if u > 0.0:\n            lo = x", "        if u < 0.0:\n            lo = x",
           "Newton's bracket updated on the wrong side"),
    # ------------------------------------------------------------------ the mode logic at rest
    Mutant("modes.fs_gap_plus", "modes", _M, "gap_plus = offset - excess if base == 1 else (base - 1) * f_c - excess + offset",
           "gap_plus = offset - excess if base == 1 else (base - 1) * f_c + excess + offset", "φ − f_s computed as φ − 2f_c + f_s off the boundary"),
    Mutant("modes.fs_gap_minus_fc", "modes", _M, "gap_minus = offset + excess if base == -1 else (base + 1) * f_c + excess + offset",
           "gap_minus = offset + excess if base == -1 else (base + 1) + excess + offset", "φ + f_s without the factor f_c"),
    Mutant("modes.boundary_offset_sign", "modes", _M, "return 1, 0.0 * offset + excess, 1 if sigma > 0 else 0",
           "return 1, 0.0 * offset - excess, 1 if sigma > 0 else 0", "a state put on +f_s is stored at +(2f_c − f_s)"),
    Mutant("modes.boundary_minus_offset", "modes", _M, "return -1, 0.0 * offset - excess, -1 if sigma < 0 else 0",
           "return -1, 0.0 * offset + excess, -1 if sigma < 0 else 0", "a state put on −f_s is stored at −(2f_c − f_s)"),
    Mutant("modes.row_fs_ignored", "modes", _M, "    if f_s is not None:\n        f_c = f_s  # the rows at rest",
           "    if f_s is None:\n        f_c = f_s  # the rows at rest", "the exact table reads the rows at rest with f_c, not f_s"),
    Mutant("kernel.after_slip_clamp_sign", "modes", _KER, "        offset = 0.0 * offset\n    return mode_at_rest",
           "        offset = -offset\n    return mode_at_rest", "the end-of-slip rule mirrors a wrong-sign offset instead of zeroing it"),
    # ------------------------------------------------------------------ the hunting proof and map
    Mutant("hp.krawczyk_lower_end", "hunting", _HP, "return bool((k - lo) > 0) and bool((hi - k) > 0)",
           "return bool((k - lo) > -1) and bool((hi - k) > 0)", "Krawczyk inclusion: the lower end not checked"),
    Mutant("hp.krawczyk_upper_end", "hunting", _HP, "return bool((k - lo) > 0) and bool((hi - k) > 0)",
           "return bool((k - lo) > 0) or bool((hi - k) > 0)", "Krawczyk inclusion: one end suffices"),
    Mutant("hp.first_zero_gives_up_proved", "hunting", _HP,
           "            if pieces > _MAX_PIECES or piece[1] - piece[0] < floor or bool(ball <= 0):\n                return False, pieces",
           "            if pieces > _MAX_PIECES or piece[1] - piece[0] < floor or bool(ball <= 0):\n                return True, pieces",
           "the first-zero search takes giving up for positive"),
    Mutant("hp.ball_with_zero_positive", "hunting", _HP, "        ball = value(a, b)\n        if bool(ball > 0):\n            continue",
           "        ball = value(a, b)\n        if not bool(ball <= 0):\n            continue", "a ball of v that contains 0 counts as positive"),
    Mutant("hp.decreasing_from_box", "hunting", _HP, "_, _, dyM = M.state(S, M.ball(t_a, t_hi))",
           "_, _, dyM = M.state(S, M.ball(t_lo, t_hi))", "∂v/∂τ < 0 checked on the final box only, not from τ_a"),
    Mutant("hp.stick_band_fc", "hunting", _HP, "return bool(phi > -f_s) and bool(phi < f_s)",
           "return bool(phi > -f_s - 1) and bool(phi < f_s + 1)", "the stick check accepts |φ₁| < f_s + 1"),
    Mutant("hp.sigma_positive", "hunting", _HP, "return params.f_s > params.f_c and 0 < s_lo < s_hi and 0 < t_a < t_lo < t_hi",
           "return params.f_s > params.f_c and s_lo < s_hi and 0 < t_a < t_lo < t_hi", "σ > 0 no longer required of the box"),
    Mutant("hmap.exit_time_fs", "hunting", _HM, "return MapStep(sigma, tuple(slips), (e * self.f_s - phi) / ys, ys, \"exit\")",
           "return MapStep(sigma, tuple(slips), (e * self.f_c - phi) / ys, ys, \"exit\")", "the map's stick lasts until ±f_c"),
    Mutant("hmap.start_offset_sign", "hunting", _HM, "p = d * self.excess  # φ - d f_c at φ = d f_s",
           "p = -d * self.excess  # φ - d f_c at φ = d f_s", "the map's slip starts at φ = d(2f_c − f_s)"),
    Mutant("hmap.derivative_sign", "hunting", _HM, "dtau = -dy_dsigma[2] / dy_dtau[2]", "dtau = dy_dsigma[2] / dy_dtau[2]",
           "P'(σ) with the implicit derivative's sign flipped",
           equivalent="dy/dτ[0] = σ' = −k_i v vanishes at the slip's end (v = 0), so dy_dτ[0]·dτ is 0 whatever dτ's sign"),
    # ------------------------------------------------------------------ the cross-check
    Mutant("cc.integral_v2_fc", "cross-check", _AL, "y[..., 1] -= kk * self.f_c", "y[..., 1] -= kk",
           "∫v² of a slip about (0, k, 0) instead of (0, k f_c, 0)"),
    Mutant("cc.mode_table_fc", "cross-check", _MT, "np.abs(xs[..., 1]) - f_c) / L", "np.abs(xs[..., 1]) - 1.0) / L",
           "the mode table's stick band |φ| ≤ 1 instead of f_c"),
    Mutant("cc.nan_slack_passes", "cross-check", _PR, "own = int(np.count_nonzero((r < -rtol) | (np.isnan(r) & self.mask)))",
           "own = int(np.count_nonzero((r < -rtol)))", "a NaN slack is not counted as a failure"),
    Mutant("cc.event_value_v", "cross-check", _AL, "x[..., 2] = np.where(kind_s < 3, 0.0, x[..., 2])",
           "x[..., 2] = np.where(kind_s < 0, 0.0, x[..., 2])", "events keep their rounding residue in v",
           equivalent="the kernel stores v = 0.0 exactly in every event state (ev_x[n, 2] = 0.0), so the replaced values are already 0"),
    # ------------------------------------------------------------------ the obligations machinery
    Mutant("ob.run_status", "obligations", _OB, "status=HOLDS if outcome.holds else FAILS,", "status=HOLDS,",
           "an obligation holds whatever its verdict"),
    Mutant("ob.crash_holds", "obligations", _OI, "status=FAILS,\n                seconds=time.perf_counter() - start, reason=f\"error",
           "status=\"holds\",\n                seconds=time.perf_counter() - start, reason=f\"error",
           "an obligation that raises is reported as holding"),
    Mutant("ob.registry_drops_modes", "obligations", _OI, "        MatricesRuntime, ModesRuntime, PNormRuntime,",
           "        MatricesRuntime, PNormRuntime,", "the registry leaves out model.modes_runtime"),
    Mutant("ob.holds_property", "obligations", _OB, "        return self.status == HOLDS", "        return self.status != FAILS",
           "Result.holds as status ≠ fails (a status that is neither would hold)"),
)

# What the test suite runs on a mutant that ``check`` and ``verify`` both miss (per target; a mutant's own
# ``tests`` come first).
_TESTS = {
    "kernel": ("tests/simulation/test_kernel_mutants.py", "tests/simulation/test_stiction.py", "tests/simulation/test_event.py"),
    "modes": ("tests/simulation/test_kernel_mutants.py", "tests/simulation/test_stiction.py", "tests/simulation/test_event.py", "tests/simulation/test_modes.py"),
    "hunting": ("tests/certify/test_hunting_proof_mutants.py", "tests/hunting/test_map_mutants.py", "tests/hunting/test_certificate.py", "tests/hunting/test_map.py"),
    "cross-check": ("tests/crosscheck/test_along_mutants.py", "tests/crosscheck/test_mode_table.py", "tests/crosscheck/test_lemma2.py", "tests/crosscheck/test_property.py",
                    "tests/crosscheck/test_along.py"),
    "obligations": ("tests/obligations/test_base_mutants.py", "tests/obligations/test_model.py"),
}
NEW = tuple(replace(m, tests=m.tests or _TESTS[m.target]) for m in NEW)

MUTANTS = MUTANTS + NEW

_QM = "symbolic_friction/_model/quadratic.py"
_QV = "symbolic_friction/_certify/quadratic.py"
_CO = "symbolic_friction/_certify/copositive.py"
_Q_TESTS = ("tests/certify/test_quadratic.py", "tests/obligations/test_quadratic.py")
QUADRATIC = tuple(replace(m, tests=_Q_TESTS) for m in (
    Mutant("q.p23_sign", "model", _QM, "p23 = k_i * p11 - k_v * p22", "p23 = k_i * p11 + k_v * p22",
           "the quadratic template's P₂₃ with a sign slip (the first row of AᵀP + PA no longer vanishes)"),
    Mutant("q.band_off", "model", _QM, "off = k_i * s * k[0][0] + k_v * k[0][2]", "off = k_i * k[0][0] + k_v * k[0][2]",
           "the band form ignores the sign of σ"),
    Mutant("q.exit_cross", "model", _QM, "cross = k[0][2] - p[1][1]", "cross = k[0][2] + p[1][1]",
           "the exit form at φ = ±f_c takes the favourable sign of σv"),
    Mutant("q.undecided_holds", "verifier", _QV, "f\"{text}: {decision.reason}{verdict}\", decision.holds is True)",
           "f\"{text}: {decision.reason}{verdict}\", decision.holds is not False)",
           "an undecided copositivity premise counts as proved"),
    Mutant("co.pair", "verifier", _CO, "return b >= 0 or b * b <= a * c", "return b * b <= a * c",
           "a 2×2 face with a large positive off-diagonal is refused (or, with b < 0, the test is unchanged)"),
    Mutant("co.hadeler_sign", "verifier", _CO, "            if total > 0:", "            if total > -1:",
           "Hadeler's 3×3 inequality accepted with a slack of 1"),
    Mutant("co.nonneg_shortcut", "verifier", _CO, "if all(m[i][j] >= 0 for i in range(n) for j in range(n)):",
           "if all(m[i][j] >= -1 for i in range(n) for j in range(n)):", "the all-nonnegative shortcut accepts entries ≥ −1"),
    Mutant("co.psd_shortcut", "verifier", _CO, "if all(d >= 0 for d in minors):", "if all(d >= 0 for d in minors[:3]):",
           "the semidefinite shortcut reads only the diagonal minors"),
    Mutant("co.diagonal", "verifier", _CO, "        if m[i][i] < 0:", "        if m[i][i] < -1:",
           "a diagonal entry down to −1 passes"),
))
MUTANTS = MUTANTS + QUADRATIC

_SF = "symbolic_friction/_certify/sup_flow.py"
SUP_FLOW_TAIL = (
    Mutant("sf.tail_rate_paper", "verifier", _SF,
           "tuple(tuple(-x for x in row) for row in quad.lyapunov_rate_entries(k_p, k_i, k_v, p_tail))),",
           "tuple(tuple(-x for x in row) for row in quad.lyapunov_rate_entries(k_p, k_i, k_v, "
           "lyapunov_matrix_entries(k_p, k_i, k_v)))),",
           "the rate premise decided for the paper's P whatever tail P the file gives"),
    Mutant("sf.tail_lower_paper", "verifier", _SF,
           'Semidefinite("sup_flow.exit", f"P − p·I ⪰ 0 ({whose})", _sub(p_tail, _scaled_identity(3, p))),',
           'Semidefinite("sup_flow.exit", f"P − p·I ⪰ 0 ({whose})", _sub(p_tail, _scaled_identity(3, p - p))),',
           "P − pI ⪰ 0 decided as P ⪰ 0: the tail's 1/p is not bounded"),
    Mutant("sf.horizon_strict", "verifier", _SF, 'pieces[-1].start, ">=", zero))', 'pieces[-1].start, ">", zero))',
           "the horizon T = 0 refused (a sound one-piece certificate is not proved)"),
    Mutant("sf.tail_entries_swapped", "verifier", _SF, 'return tuple(tuple(c[f"{min(i, j)}{max(i, j)}"] for j in (1, 2, 3)) for i in (1, 2, 3))',
           'return tuple(tuple(c[f"{min(i, j)}{max(i, j)}"] for i in (1, 2, 3)) for j in (3, 2, 1))',
           "the file's tail P read in the wrong order"),
    # the key under which the self-check shares a flow premise's verdict among files (shared_flow_decisions): each
    # number decide_flow reads must be in it, or a false file inherits a true file's verdict
    Mutant("sf.key_drops_c2", "verifier", _SF, 'return common + (_exact_key(cert.constants["c2"]),)', "return common",
           "c₂ ≥ ‖e^{At}‖² shared among files with different c₂"),
    Mutant("sf.key_drops_forms", "verifier", _SF,
           "tuple((s, _exact_key(*(x for row in k for x in row))) for s, k in piece.signed_forms()))", "())",
           "an exit premise shared among pieces with different forms"),
)
MUTANTS = MUTANTS + SUP_FLOW_TAIL

_SF2 = "symbolic_friction/_certify/sup_flow_v2.py"
_MQ = "symbolic_friction/_model/quadratic.py"
_MS = "symbolic_friction/_model/sup_flow.py"
_SFE = "symbolic_friction/_certify/sup_flow_enclosure.py"
SUP_FLOW_V2 = (
    Mutant("sf2.k12_sign", "verifier", _SF2, 's * k[0][1], ">=", zero))', 'abs(k[0][1]), ">=", zero))',
           "K±₁₂ of either sign accepted (the rate form's (1,1) entry 2sK₁₂ may be negative)"),
    Mutant("sf2.coupling_swapped", "verifier", _SF2, "model.coupling_block(piece.form(1), piece.form(-1))",
           "model.coupling_block(piece.form(-1), piece.form(1))", "U⁺ ≤ U⁻ on σ = 0 asked instead of U⁻ ≤ U⁺"),
    Mutant("sf2.ell_sign", "verifier", _SF2, 'f"ell{j + 1} ≥ 0", ell[j], ">=", zero)', 'f"ell{j + 1} ≥ 0", abs(ell[j]), ">=", zero)',
           "a negative ℓ accepted"),
    Mutant("sf2.no_drag_maps", "verifier", _SF2, "        if not any(self.ell):\n            return ()",
           "        if any(self.ell) or True:\n            return ()",
           "the drag exit form and c₂ ≥ ‖e^{At}D_ℓ‖² never decided"),
    Mutant("sf2.forms_same_sign", "verifier", _SF2, "return ((1, self.form(1)), (-1, self.form(-1)))",
           "return ((1, self.form(1)), (-1, self.form(1)))", "the exits of σ < 0 decided with K⁺"),
    Mutant("mq.drag_rate_sign", "model", _MQ, "rate[i][j] + k[i][2] * ell[j] + ell[i] * k[j][2]",
           "rate[i][j] + 2 * (k[i][2] * ell[j] + ell[i] * k[j][2])", "the friction drag counted twice in the rate form"),
    Mutant("mq.drag_band_entry", "model", _MQ, "drag = ((2 * k[0][2] * l1, k[0][2] * l3 + k[2][2] * l1)",
           "drag = ((2 * k[0][2] * l1 + k[2][2], k[0][2] * l3 + k[2][2] * l1)", "the band's drag block gains K₃₃ on its diagonal"),
    Mutant("ms.drag_map_sign", "model", _MS, "return ((s, zero, zero), (-ell[0], -one - ell[1], -ell[2]), (zero, zero, one))",
           "return ((s, zero, zero), (ell[0], -one - ell[1], ell[2]), (zero, zero, one))", "D_ℓ with +ℓ: the exit point moved"),
    Mutant("sfe.drag_pullback_skipped", "verifier", _SFE, "    for d in maps:\n        m = flint.arb_mat",
           "    for d in maps[:0]:\n        m = flint.arb_mat", "c₂ not held against ‖e^{At}D_ℓ‖²"),
)
MUTANTS = MUTANTS + SUP_FLOW_V2

KERNEL_RESIDUAL = (
    Mutant("ker.event_residual", "kernel", _KER, "ev_res[n_ev] = residual", "ev_res[n_ev] = 0.0",
           "the residual abs(v) at an event is dropped (the mode table's v = 0 at events is then vacuous)",
           tests=("tests/simulation/test_kernel_mutants.py::test_event_residual_is_v_where_the_slip_ended",)),
)
MUTANTS = MUTANTS + KERNEL_RESIDUAL

_L3 = "symbolic_friction/_crosscheck/lemma3.py"
_CL1 = "symbolic_friction/_obligations/claim1.py"
# Issue 33, item 5: the trusted base's last gaps (each was a survivor of a hidden mutant set before its fix).
TRUSTED_GAPS = (
    Mutant("cx.c2_factor2", "cross-check", _L3, "rel = (c2 * a.d2 - a.V) / scale", "rel = (2 * c2 * a.d2 - a.V) / scale",
           "Lemma 3's V ≤ c₂|x|²_𝒜 checked with 2c₂"),
    Mutant("cx.V_half", "cross-check", _L3, "rel = (c2 * a.d2 - a.V) / scale", "rel = (c2 * a.d2 - a.V / 2) / scale",
           "Lemma 3's V ≤ c₂|x|²_𝒜 checked with V/2"),
    Mutant("cx.c2_exact_factor2", "cross-check", _L3, 'not (V(params, xq) <= Fraction(certificate.exact["c2"]) *',
           'not (V(params, xq) <= 2 * Fraction(certificate.exact["c2"]) *',
           "the exact re-decision of V ≤ c₂|x|²_𝒜 at a witness made with 2c₂"),
    Mutant("cx.near_A_skip", "cross-check", _L3, "return Evaluation(rel, a.in_R & a.off_A, witness,",
           "return Evaluation(rel, a.in_R & a.far, witness,", "V ≤ c₂|x|²_𝒜 skips the points with |x|²_𝒜 < 10⁻⁶L²"),
    Mutant("cx.hatV_interval_ends", "cross-check", _L3, "run &= a.in_Rhat[:, :-1] | a.in_Rhat[:, 1:]",
           "run &= a.in_Rhat[:, :-1] & a.in_Rhat[:, 1:]", "V̂ nonincreasing skips the R̂ intervals that end at an event"),
    Mutant("cx.hatV_scale_fc", "cross-check", _L3, "star[:, 1] = k * a.f_c", "star[:, 1] = k",
           "the interior points of an R̂ interval flowed about (0, k, 0) instead of (0, k f_c, 0)"),
    Mutant("kernel.scan_fourth_order", "kernel", _KF, "slack = grow * (max(u2_prev, u2_next) + extra)",
           "slack = grow * max(u2_prev, u2_next)", "the scan's bound on |u''| on a cell without its fourth-order term"),
    Mutant("kernel.scan_fourth_order_fast", "kernel", _KF, "extra = grow * min(m4 * r_p,", "extra = 0.0 * min(m4 * r_p,",
           "the fast table's fourth-order term zeroed"),
    Mutant("kernel.rounding_swap_kp_ki", "kernel", _KER,
           "K[I_GAIN_KI] * abs(float(z0[0])) + K[I_GAIN_KP] * abs(float(z0[1]))",
           "K[I_GAIN_KP] * abs(float(z0[0])) + K[I_GAIN_KI] * abs(float(z0[1]))",
           "the rounding tolerance of φ = −k_i e_i − k_p s at rest with k_i and k_p swapped"),
    Mutant("ob.claim1_undecided_sign", "obligations", _CL1, "if finite and sign_of(T) != 1:",
           "if finite and sign_of(T) == -1:", "claim1.cases accepts a stick duration of undecided sign (or 0)"),
)
_GAP_TESTS = {
    "cross-check": ("tests/crosscheck/test_trusted_gaps.py",),
    "kernel": ("tests/simulation/test_scan_graze.py", "tests/crosscheck/test_trusted_gaps.py"),
    "obligations": ("tests/obligations/test_claim1_duration.py",),
}
# check catches each of them (its self-test, kernel rows or decision cases); the tests are the fallback
TRUSTED_GAPS = tuple(replace(m, tests=_GAP_TESTS[m.target]) for m in TRUSTED_GAPS)
MUTANTS = MUTANTS + TRUSTED_GAPS

FAST: tuple[str, ...] = ("V.at_rest", "verify.drop_c2")
"""The subset the default test run executes (one model and one verifier mutant)."""
