#!/usr/bin/env python3
"""Derives the position residual of every closed-form profile family of trajkit's online
generator (crates/trajkit/src/otg/families.rs) as a polynomial in the family's free parameter
and writes the coefficient functions as Rust.

Each family is a list of constant-jerk segments whose durations are polynomials in the free
parameter s, and possibly in one more unknown w with w² = W(s) (a second acceleration level
tied to s by the velocity equation). The displacement is integrated symbolically, powers of w
are reduced with w² = W(s), and the residual "displacement − d" is written as A(s) + w·B(s).
The Rust side solves A = 0 (no w) or A² − W·B² = 0 and recovers w = −A/B.

Usage: tools/otg_coefficients.py > crates/trajkit/src/otg/families_gen.rs && cargo fmt --all
(creates tools/.venv-otgcoeff with sympy on first run unless sympy is importable).
"""
import os
import sys
from pyenv import use_venv

HERE = os.path.dirname(os.path.abspath(__file__))


try:
    import sympy  # noqa: F401
except ImportError:
    use_venv("otgcoeff", ["sympy==1.14.*"])
import sympy as sp  # noqa: E402


def rust(e):
    """Prints a sympy expression (sums, products, integer powers, rationals, symbols) as f64
    Rust, parenthesizing every sum inside a product or power."""
    if e.is_Symbol:
        return str(e)
    if e.is_Integer:
        return f"{int(e)}.0"
    if e.is_Rational:
        return f"({e.p}.0 / {e.q}.0)"
    if e.is_Add:
        terms = [rust(t) for t in e.as_ordered_terms()]
        out = terms[0]
        for t in terms[1:]:
            out += f" - {t[1:]}" if t.startswith("-") and not t.startswith("-(") else f" + {t}"
        return out
    if e.is_Mul:
        c, _ = e.as_coeff_Mul()
        if c < 0:
            return "-" + rust(-e)
        facs = [wrap(f) for f in e.as_ordered_factors()]
        return "*".join(facs)
    if e.is_Pow:
        b, x = e.as_base_exp()
        if x == -1:
            return f"{wrap(b, True)}.recip()"
        if x.is_Integer:
            return f"{wrap(b, True)}.powi({int(x)})"
        if x == sp.Rational(1, 2):
            return f"{wrap(b, True)}.sqrt()"
    raise SystemExit(f"cannot print {e!r}")


def wrap(e, tight=False):
    out = rust(e)
    if e.is_Add or (e.is_Number and e < 0):
        return f"({out})"
    if tight and (e.is_Mul or (e.is_Rational and not e.is_Integer)):
        return f"({out})"
    return out


s, w = sp.symbols("s w")
a0, af, v0, vf, d, j, amax, amin, T = sp.symbols("a0 af v0 vf d j amax amin t")
d1, d2, A1, A2 = sp.symbols("d1 d2 al1 al2")
SIGNS = (d1, d2)


def integrate(segs, v_start, a_start):
    p, v, a = 0, v_start, a_start
    for t, jk in segs:
        p = p + v * t + a * t**2 / 2 + jk * t**3 / 6
        v = v + a * t + jk * t**2 / 2
        a = a + jk * t
    return p, v, a


def reduce_signs(e):
    """d1, d2 are ±1: reduce their powers modulo 2."""
    e = sp.expand(e)
    for sg in SIGNS:
        e = sp.expand(e.replace(lambda x: x.is_Pow and x.base == sg,
                                lambda x: sg ** (int(x.exp) % 2)))
    return e


def split(expr, W):
    """expr (polynomial in w) reduced modulo w² − W: returns (A, B) with expr = A + w·B."""
    e = sp.expand(expr)
    if W is None:
        return e, sp.Integer(0)
    pw = sp.Poly(e, w)
    A, B = sp.Integer(0), sp.Integer(0)
    for (k,), c in pw.terms():
        base = W ** (k // 2)
        if k % 2 == 0:
            A += c * base
        else:
            B += c * base
    return reduce_signs(A), reduce_signs(B)


def coeffs(e):
    e = sp.expand(e)
    if e == 0:
        return [sp.Integer(0)]
    p = sp.Poly(e, s)
    n = p.degree()
    return [sp.simplify(p.coeff_monomial(s**k)) for k in range(n + 1)]


def check(segs, W, vend, aend):
    """The family's velocity and acceleration equations hold identically."""
    _, v, a = integrate(segs, v0, a0)
    for got, want in ((v, vend), (a, aend)):
        r = reduce_signs(sp.expand(got - want))
        if W is not None:
            A, B = split(r, W)
            r = sp.expand(A) + sp.expand(B)
            if sp.simplify(A) != 0 or sp.simplify(B) != 0:
                raise SystemExit(f"velocity/acceleration equation fails: {A} + w {B}")
        elif sp.simplify(r) != 0:
            raise SystemExit(f"velocity/acceleration equation fails: {r}")


def family(name, doc, args, segs, W, vend=vf, aend=af):
    check(segs, W, vend, aend)
    p, _, _ = integrate(segs, v0, a0)
    A, B = split(reduce_signs(p - d), W)
    ca, cb = coeffs(A), coeffs(B) if W is not None else []
    cw = coeffs(W) if W is not None else []
    cp = coeffs(A**2 - W * B**2) if W is not None else ca
    exprs = ca + cb + cw + cp
    repl, red = sp.cse(exprs, symbols=sp.numbered_symbols("x"))
    out = [f"/// {doc}", "#[allow(clippy::all, unused_variables)]",
           f"pub(crate) fn {name}({', '.join(a + ': f64' for a in args)}) -> Resid {{"]
    for sym, e in repl:
        out.append(f"    let {sym} = {rust(e)};")
    na, nb = len(ca), len(cb)
    fa = [rust(e) for e in red[:na]]
    fb = [rust(e) for e in red[na:na + nb]]
    nw = len(cw)
    fw = [rust(e) for e in red[na + nb:na + nb + nw]]
    fp = [rust(e) for e in red[na + nb + nw:]]

    def arr(xs, n):
        xs = [x if x not in ("0",) else "0.0" for x in xs]
        return "[" + ", ".join(xs + ["0.0"] * (n - len(xs))) + "]"
    out.append("    Resid {")
    out.append(f"        a: {arr(fa, 7)},")
    out.append(f"        na: {na},")
    out.append(f"        b: {arr(fb, 7)},")
    out.append(f"        nb: {nb},")
    out.append(f"        w: {arr(fw, 3)},")
    out.append(f"        p: {arr(fp, 7)},")
    out.append(f"        np: {len(fp)},")
    out.append("    }")
    out.append("}")
    print("\n".join(out))
    print()
    sys.stderr.write(f"{name}: deg A {na - 1}, deg B {nb - 1}, deg W {len(cw) - 1}, deg P {len(fp) - 1}\n")


def main():
    print("// Generated by tools/otg_coefficients.py; do not edit by hand.")
    print("//! Position residuals of the closed-form profile families as polynomials (generated).")
    print()
    print("use super::families::Resid;")
    print()
    base = ["a0", "af", "v0", "vf", "d", "j"]
    dv = vf - v0
    # Step 1, positive direction: a0 ↗ α1 ↘ α2 ↗ af (s = α1, w = α2).
    K = j * dv + (a0**2 - af**2) / 2
    family("s1_none", "a₀ ↗ s ↘ w ↗ a_f; w² = s² − K.", base,
           [((s - a0) / j, j), ((s - w) / j, -j), ((af - w) / j, j)], s**2 - K)
    # acc0: plateau at amax for τ₁, then ↘ s ↗ af (s = α2).
    c0 = amax**2 + (af**2 - a0**2) / 2 - j * dv
    t1 = (s**2 - c0) / (j * amax)
    family("s1_acc0", "a₀ ↗ a_max (hold τ₁(s)) ↘ s ↗ a_f.", base + ["amax"],
           [((amax - a0) / j, j), (t1, 0), ((amax - s) / j, -j), ((af - s) / j, j)], None)
    # acc1: a0 ↗ s ↘ amin (hold τ₂(s)) ↗ af.
    t2 = ((2 * s**2 - a0**2 - 2 * amin**2 + af**2) / (2 * j) - dv) / (-amin)
    family("s1_acc1", "a₀ ↗ s ↘ a_min (hold τ₂(s)) ↗ a_f.", base + ["amin"],
           [((s - a0) / j, j), ((s - amin) / j, -j), (t2, 0), ((af - amin) / j, j)], None)
    # acc0_acc1: s = τ1.
    t2 = ((2 * amax**2 - a0**2 - 2 * amin**2 + af**2) / (2 * j) + amax * s - dv) / (-amin)
    family("s1_acc01", "a₀ ↗ a_max (hold s) ↘ a_min (hold τ₂(s)) ↗ a_f.", base + ["amax", "amin"],
           [((amax - a0) / j, j), (s, 0), ((amax - amin) / j, -j), (t2, 0),
            ((af - amin) / j, j)], None)

    # Two velocity changes through (v_c, 0) with a cruise τ between them. Change 1 ramps the
    # acceleration towards α (jerk d1·j), optionally holds α for τ₁, and ramps back to 0;
    # change 2 ramps towards β (jerk d2·j), optionally holds for τ₂, and ramps to a_f.
    def two(name, doc, alpha, beta, tau1, tau2, W, vc, timed):
        pre = [((alpha - a0) * d1 / j, d1 * j), (tau1, 0), (alpha * d1 / j, -d1 * j)]
        post = [(beta * d2 / j, d2 * j), (tau2, 0), ((beta - af) * d2 / j, -d2 * j)]
        if timed:
            tau = T - sum(t for t, _ in pre + post)
            segs = pre + [(tau, 0)] + post
        else:
            segs = pre + post
        family(name, doc, base + ["d1", "d2", "al1", "al2"] + (["t"] if timed else []), segs, W)

    for timed in (False, True):
        suf = "_t" if timed else ""
        what = "cruise for the rest of t" if timed else "no cruise"
        # NN: s = α, w = β.
        vc = v0 + d1 * (2 * s**2 - a0**2) / (2 * j)
        Wb = (af**2 + 2 * d2 * j * (vf - vc)) / 2
        two("two_nn" + suf, f"Two changes without plateaus ({what}); s = α, w = β.",
            s, w, 0, 0, reduce_signs(Wb), vc, timed)
        # PN: α = al1 held for τ₁, s = β.
        vc = vf - d2 * (2 * s**2 - af**2) / (2 * j)
        tau1 = (vc - v0 - d1 * (2 * A1**2 - a0**2) / (2 * j)) / A1
        two("two_pn" + suf, f"Plateau at al1 in change 1 ({what}); s = β.",
            A1, s, tau1, 0, None, vc, timed)
        # NP: s = α, β = al2 held for τ₂.
        vc = v0 + d1 * (2 * s**2 - a0**2) / (2 * j)
        tau2 = (vf - vc - d2 * (2 * A2**2 - af**2) / (2 * j)) / A2
        two("two_np" + suf, f"Plateau at al2 in change 2 ({what}); s = α.",
            s, A2, 0, tau2, None, vc, timed)
        # PP: s = v_c.
        tau1 = (s - v0 - d1 * (2 * A1**2 - a0**2) / (2 * j)) / A1
        tau2 = (vf - s - d2 * (2 * A2**2 - af**2) / (2 * j)) / A2
        two("two_pp" + suf, f"Plateaus in both changes ({what}); s = v_c.",
            A1, A2, tau1, tau2, None, s, timed)


main()
