"""numba code of :mod:`tolalloc.montecarlo.engines.numba_engine` (imported only when the compiled engine is used).

Element-wise loops over samples are branch-free so that LLVM vectorises them; reductions that do not
need a fixed order (sums for the moments, extrema) are in ``fastmath`` functions.
"""

import math

import numpy as np
from numba import njit

CHUNK = 256
_TWO_OVER_PI = 6.36619772367581382433e-01
_PIO2_1 = 1.57079632673412561417e+00  # first 33 bits of pi/2 (n * _PIO2_1 exact for |n| < 2^20)
_PIO2_1T = 6.07710050650619224932e-11  # pi/2 - _PIO2_1
_S1, _S2, _S3 = -1.66666666666666324348e-01, 8.33333333332248946124e-03, -1.98412698298579493134e-04
_S4, _S5, _S6 = 2.75573137070700676789e-06, -2.50507602534068634195e-08, 1.58969099521155010221e-10
_C1, _C2, _C3 = 4.16666666666666019037e-02, -1.38888888888741095749e-03, 2.48015872894767294178e-05
_C4, _C5, _C6 = -2.75573143513906633035e-07, 2.08757232129817482790e-09, -1.13596475577881948265e-11
_P0, _P1, _P2 = -8.750608600031904122785e-01, -1.615753718733365076637e+01, -7.500855792314704667340e+01
_P3, _P4 = -1.228866684490136173410e+02, -6.485021904942025371773e+01
_Q0, _Q1, _Q2 = 2.485846490142306297962e+01, 1.650270098316988542046e+02, 4.328810604912902668951e+02
_Q3, _Q4 = 4.853903996359136964868e+02, 1.945506571482613964425e+02
_PIO4, _PIO2, _PI = 7.85398163397448309616e-01, 1.57079632679489661923e+00, 3.14159265358979323846e+00
_MOREBITS = 6.123233995736765886130e-17  # pi/2 - _PIO2


@njit(nogil=True, cache=True, error_model="numpy", inline="always")
def _sincos(x):
    """sin and cos of x [rad], |x| < 1e5: Cody-Waite reduction by pi/2, fdlibm kernels (< 1 ulp)."""
    n = math.floor(x * _TWO_OVER_PI + 0.5)
    y = (x - n * _PIO2_1) - n * _PIO2_1T
    z = y * y
    w = z * z
    r = _S2 + z * (_S3 + z * _S4) + z * w * (_S5 + z * _S6)
    s = y + (z * y) * (_S1 + z * r)
    rc = z * (_C1 + z * (_C2 + z * _C3)) + w * w * (_C4 + z * (_C5 + z * _C6))
    hz = 0.5 * z
    w1 = 1.0 - hz
    c = w1 + (((1.0 - w1) - hz) + z * rc)
    q = n - 4.0 * math.floor(n * 0.25)  # quadrant 0..3
    odd = (q == 1.0) | (q == 3.0)
    si = c if odd else s
    co = s if odd else c
    si = -si if q >= 2.0 else si
    co = -co if ((q == 1.0) | (q == 2.0)) else co
    return si, co


@njit(nogil=True, cache=True, error_model="numpy", inline="always")
def _atan2(y, x):
    """atan2 with Cephes' rational arctangent on [0, 0.66] (about 1 ulp)."""
    ax, ay = abs(x), abs(y)
    sf = 1.0 if ay > ax else 0.0  # only selects of constants and values: the loops stay vectorisable
    num = ay if ay <= ax else ax
    den = ax if ay <= ax else ay
    a = num / (den if den > 0.0 else 1.0)
    bf = 1.0 if a > 0.66 else 0.0
    t = (a - bf) / (bf * a + 1.0)  # a, or (a - 1) / (a + 1) with pi/4 added below
    z = t * t
    p = z * ((((_P0 * z + _P1) * z + _P2) * z + _P3) * z + _P4) / (((((z + _Q0) * z + _Q1) * z + _Q2) * z + _Q3) * z + _Q4)
    r = t * p + t
    r = bf * _PIO4 + (r + bf * (0.5 * _MOREBITS))
    r = sf * _PIO2 + (sf * _MOREBITS + (1.0 - 2.0 * sf) * r)
    xf = 1.0 if x < 0.0 else 0.0
    r = xf * _PI + (xf * (2.0 * _MOREBITS) + (1.0 - 2.0 * xf) * r)
    pos = (y > 0.0) | ((y == 0.0) & (1.0 / y > 0.0))  # the sign of y, also of a signed zero
    return r if pos else -r


@njit(nogil=True, cache=True, error_model="numpy")
def _chain(V, base, nc, fi, fk, fcf, fd, endoff, home, X, Y, th, S, C):
    """The PoseProgram (errormodel.pose_program) of one pose on samples ``base .. base + nc`` into X (3, 4, CHUNK)."""
    for i in range(3):
        for j in range(4):
            h = home[i, j]
            for n in range(nc):
                X[i, j, n] = h
    for f in range(fi.shape[0]):
        typ, ncf = fi[f, 0], fi[f, 1]
        if typ < 0:
            break
        d = fd[f]
        const = d[0]
        if ncf > 0:  # amount: same operation order as FastChain._amount
            row, cf = V[fk[f, 0], base:base + nc], fcf[f, 0]
            for n in range(nc):
                th[n] = row[n] * cf
            for j in range(1, ncf):
                row, cf = V[fk[f, j], base:base + nc], fcf[f, j]
                for n in range(nc):
                    th[n] = th[n] + row[n] * cf
            if const != 0.0:
                for n in range(nc):
                    th[n] = th[n] + const
        else:
            for n in range(nc):
                th[n] = const
        if typ == 0:
            for r in range(3):
                vr = d[9 + r]
                if vr == 0.0:
                    continue
                Xr = X[r, 3]
                if vr == 1.0:
                    for n in range(nc):
                        Xr[n] = Xr[n] + th[n]
                else:
                    for n in range(nc):
                        Xr[n] = Xr[n] + th[n] * vr
            continue
        if ncf > 0:
            for n in range(nc):
                S[n], C[n] = _sincos(th[n])
        else:
            for n in range(nc):
                S[n], C[n] = d[12], d[13]
        if typ == 1:
            a, b, sg = fi[f, 2], fi[f, 3], d[1]
            Xa, Xb = X[a], X[b]
            sha, shb = d[2 + a], d[2 + b]
            if sha != 0.0:
                for n in range(nc):
                    Xa[3, n] = Xa[3, n] + sha
            if shb != 0.0:
                for n in range(nc):
                    Xb[3, n] = Xb[3, n] + shb
            for j in range(4):
                xa, xb = Xa[j], Xb[j]
                if sg > 0:
                    for n in range(nc):
                        u, v = xa[n], xb[n]
                        xa[n] = u * C[n] - v * S[n]
                        xb[n] = v * C[n] + u * S[n]
                else:
                    for n in range(nc):
                        u, v = xa[n], xb[n]
                        xa[n] = u * C[n] + v * S[n]
                        xb[n] = v * C[n] - u * S[n]
        else:
            for r in range(3):
                for j in range(4):
                    sh = d[2 + r] if j == 3 else 0.0
                    for n in range(nc):
                        Y[r, j, n] = X[r, j, n] + sh
            for n in range(nc):
                s, c = S[n], C[n]
                for r in range(3):
                    c0 = (((1.0 if r == 0 else 0.0) + d[23 + 3 * r]) + d[14 + 3 * r] * s) - d[23 + 3 * r] * c
                    c1 = (((1.0 if r == 1 else 0.0) + d[24 + 3 * r]) + d[15 + 3 * r] * s) - d[24 + 3 * r] * c
                    c2 = (((1.0 if r == 2 else 0.0) + d[25 + 3 * r]) + d[16 + 3 * r] * s) - d[25 + 3 * r] * c
                    for j in range(4):
                        X[r, j, n] = (Y[0, j, n] * c0 + Y[1, j, n] * c1) + Y[2, j, n] * c2
                    X[r, 3, n] = X[r, 3, n] + d[9 + r]
        if d[8] != 0.0:
            for r in range(3):
                hw = d[5 + r]
                if hw != 0.0:
                    for n in range(nc):
                        X[r, 3, n] = X[r, 3, n] + hw * th[n]
    for r in range(3):
        if endoff[r] != 0.0:
            for n in range(nc):
                X[r, 3, n] = X[r, 3, n] + endoff[r]


@njit(nogil=True, cache=True, error_model="numpy")
def _features(Xf, nc, pc, Fo):
    """ErrorFeatures rows (dx dy dz rv(3) norm reach alpha beta gamma, then |rv|) of the chain outputs.

    ``Xf`` is X (3, 4, CHUNK) flattened and ``Fo`` (12 * CHUNK) the output rows: one base pointer each with
    constant row offsets, so that the loop vectorises without run-time alias checks.

    Returns the number of samples whose rotation error is near pi (cos < -0.999).
    """
    W = CHUNK
    p0x, p0y, p0z, r0sq, r0 = pc[0], pc[1], pc[2], pc[3], pc[4]
    q00, q01, q02, q10, q11, q12, q20, q21, q22 = pc[5], pc[6], pc[7], pc[8], pc[9], pc[10], pc[11], pc[12], pc[13]
    ca, sa, cg, sg, b0 = pc[14], pc[15], pc[16], pc[17], pc[18]
    r0pos = r0 > 0.0
    bad = 0
    for n in range(nc):
        px, py, pz = Xf[3 * W + n], Xf[7 * W + n], Xf[11 * W + n]
        dx, dy, dz = px - p0x, py - p0y, pz - p0z
        dot = (p0x * px + p0y * py + p0z * pz) - r0sq
        b1 = ca * Xf[9 * W + n] - sa * Xf[10 * W + n]
        b2 = ca * Xf[10 * W + n] + sa * Xf[9 * W + n]
        b3 = cg * Xf[4 * W + n] - sg * Xf[0 * W + n]
        b4 = cg * Xf[0 * W + n] + sg * Xf[4 * W + n]
        e00 = Xf[0 * W + n] * q00 + Xf[1 * W + n] * q01 + Xf[2 * W + n] * q02
        e01 = Xf[0 * W + n] * q10 + Xf[1 * W + n] * q11 + Xf[2 * W + n] * q12
        e02 = Xf[0 * W + n] * q20 + Xf[1 * W + n] * q21 + Xf[2 * W + n] * q22
        e10 = Xf[4 * W + n] * q00 + Xf[5 * W + n] * q01 + Xf[6 * W + n] * q02
        e11 = Xf[4 * W + n] * q10 + Xf[5 * W + n] * q11 + Xf[6 * W + n] * q12
        e12 = Xf[4 * W + n] * q20 + Xf[5 * W + n] * q21 + Xf[6 * W + n] * q22
        e20 = Xf[8 * W + n] * q00 + Xf[9 * W + n] * q01 + Xf[10 * W + n] * q02
        e21 = Xf[8 * W + n] * q10 + Xf[9 * W + n] * q11 + Xf[10 * W + n] * q12
        e22 = Xf[8 * W + n] * q20 + Xf[9 * W + n] * q21 + Xf[10 * W + n] * q22
        v0, v1, v2 = 0.5 * (e21 - e12), 0.5 * (e02 - e20), 0.5 * (e10 - e01)
        n2 = dx * dx + dy * dy + dz * dz
        num = 2.0 * dot + n2
        den = math.sqrt(num + r0sq) + r0
        sn = math.sqrt(v0 * v0 + v1 * v1 + v2 * v2)
        cosv = 0.5 * ((e00 + e11 + e22) - 1.0)
        bad += cosv < -0.999
        theta = _atan2(sn, cosv)
        u = theta / (sn if sn > 1e-300 else 1e-300)  # sn == 0: theta == 0 and v == 0
        Fo[0 * W + n], Fo[1 * W + n], Fo[2 * W + n] = dx, dy, dz
        Fo[3 * W + n], Fo[4 * W + n], Fo[5 * W + n] = v0 * u, v1 * u, v2 * u
        reach0 = math.sqrt(max(num, 0.0))  # tool point at the base origin
        Fo[6 * W + n], Fo[7 * W + n] = math.sqrt(n2), (num / den if r0pos else reach0)
        Fo[8 * W + n] = _atan2(b1, b2)
        Fo[9 * W + n] = _atan2(-Xf[8 * W + n], math.sqrt(b3 * b3 + b4 * b4)) - b0
        Fo[10 * W + n] = _atan2(b3, b4)
        Fo[11 * W + n] = theta
    return bad


@njit(nogil=True, cache=True, error_model="numpy", fastmath=True)
def _extrema_counts(FB, N, mx, mn, radii, aradii, cnt):
    hi, lo = np.empty(8), np.empty(8)
    for i in range(11):
        row = FB[i, :N]
        for k in range(8):
            hi[k] = mx[i]
            lo[k] = mn[i]
        for n0 in range(0, N - 7, 8):  # 8 lanes, unrolled: vectorised selects
            for k in range(8):
                v = row[n0 + k]
                hi[k] = v if v > hi[k] else hi[k]
                lo[k] = v if v < lo[k] else lo[k]
        a, b = mx[i], mn[i]
        for k in range(8):
            a = hi[k] if hi[k] > a else a
            b = lo[k] if lo[k] < b else b
        for n in range(N - N % 8, N):
            a = row[n] if row[n] > a else a
            b = row[n] if row[n] < b else b
        mx[i], mn[i] = a, b
    for j in range(radii.size + aradii.size):
        row = FB[6, :N] if j < radii.size else FB[11, :N]
        r = radii[j] if j < radii.size else aradii[j - radii.size]
        c = 0
        for n in range(N):
            c += row[n] < r
        cnt[j] += c


@njit(nogil=True, cache=True, error_model="numpy")
def _hist(FB, N, lo, inv_w, nb, H):
    """HistSpec.cell_index + count, same floating-point operations."""
    w = nb + 2
    for n in range(N):
        i0 = int(min(max(math.floor((FB[0, n] - lo[0]) * inv_w[0]), -1.0), float(nb)) + 1.0)
        i1 = int(min(max(math.floor((FB[1, n] - lo[1]) * inv_w[1]), -1.0), float(nb)) + 1.0)
        i2 = int(min(max(math.floor((FB[2, n] - lo[2]) * inv_w[2]), -1.0), float(nb)) + 1.0)
        H[0, i0 * w + i1] += 1
        H[1, i0 * w + i2] += 1
        H[2, i1 * w + i2] += 1


@njit(nogil=True, cache=True, error_model="numpy", fastmath=True)
def _moments(FB, N, mean, M2):
    """Two-pass moments of FB[:11, :N] (centred in place): mean (11,), co-moment matrix (11, 11)."""
    for i in range(11):
        row = FB[i, :N]
        s = 0.0
        for n in range(N):
            s += row[n]
        mu = s / N
        mean[i] = mu
        for n in range(N):
            row[n] -= mu
    for i in range(11):
        for j in range(11):
            M2[i, j] = 0.0
    for t0 in range(0, N, 512):
        t1 = min(N, t0 + 512)
        for i in range(11):
            a = FB[i, t0:t1]
            for j in range(i + 1):
                b = FB[j, t0:t1]
                acc = 0.0
                for n in range(t1 - t0):
                    acc += a[n] * b[n]
                M2[i, j] += acc
    for i in range(11):
        for j in range(i):
            M2[j, i] = M2[i, j]


@njit(nogil=True, cache=True, error_model="numpy")
def block_kernel(V, sub, fi, fk, fcf, fd, endoff, pose_c, home, radii, aradii, lo, inv_w, nb, keep,
                 mean, M2, mx, mn, cnt, H, kept):
    """One block, every pose; sub-block moments merged in order (Chan et al., as Moments.merge)."""
    m = V.shape[1]
    P = fi.shape[0]
    Xf = np.empty(12 * CHUNK)
    X = Xf.reshape(3, 4, CHUNK)
    Fo = np.empty(12 * CHUNK)
    Y = np.empty((3, 4, CHUNK))
    th, S, C = np.empty(CHUNK), np.empty(CHUNK), np.empty(CHUNK)
    FB = np.empty((12, sub))
    smean, sM2, d = np.empty(11), np.empty((11, 11)), np.empty(11)
    for p in range(P):
        for i in range(mx.shape[1]):
            mx[p, i] = -np.inf
            mn[p, i] = np.inf
    nacc = np.zeros(P, np.int64)
    for s0 in range(0, m, sub):
        N = min(sub, m - s0)
        for p in range(P):
            for c0 in range(0, N, CHUNK):
                nc = min(CHUNK, N - c0)
                _chain(V, s0 + c0, nc, fi[p], fk[p], fcf[p], fd[p], endoff[p], home, X, Y, th, S, C)
                if _features(Xf, nc, pose_c[p], Fo) > 0:
                    return False
                for i in range(12):
                    for n in range(nc):
                        FB[i, c0 + n] = Fo[i * CHUNK + n]
            _extrema_counts(FB, N, mx[p], mn[p], radii, aradii, cnt[p])
            if nb >= 0:
                _hist(FB, N, lo[p], inv_w[p], nb, H[p])
            if p == 0 and s0 < keep:
                for i in range(11):
                    for n in range(min(N, keep - s0)):
                        kept[i, s0 + n] = FB[i, n]
            _moments(FB, N, smean, sM2)
            if nacc[p] == 0:
                for i in range(11):
                    mean[p, i] = smean[i]
                    for j in range(11):
                        M2[p, i, j] = sM2[i, j]
                nacc[p] = N
            else:
                tot = nacc[p] + N
                for i in range(11):
                    d[i] = smean[i] - mean[p, i]
                    mean[p, i] = mean[p, i] + d[i] * (N / tot)
                w = nacc[p] * N / tot
                for i in range(11):
                    for j in range(11):
                        M2[p, i, j] = (M2[p, i, j] + sM2[i, j]) + (d[i] * d[j]) * w
                nacc[p] = tot
    return True


@njit(nogil=True, cache=True)
def fill_standard_normal(rng, out):
    """``rng.standard_normal(out=out)`` for a C-contiguous 2-D ``out``: numba's port of numpy's ziggurat on
    the same bit generator gives the same numbers in the same order (tested), about 2x faster here."""
    for i in range(out.shape[0]):
        row = out[i]
        for j in range(row.size):
            row[j] = rng.standard_normal()
