"""numba code of :mod:`tolalloc.kernel` (imported only when the compiled engine is used).

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


@njit(nogil=True, cache=True, inline="always")
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
    odd = q == 1.0 or q == 3.0
    si = c if odd else s
    co = s if odd else c
    si = -si if q >= 2.0 else si
    co = -co if (q == 1.0 or q == 2.0) else co
    return si, co


@njit(nogil=True, cache=True, inline="always")
def _atan2(y, x):
    """atan2 with Cephes' rational arctangent on [0, 0.66] (about 1 ulp)."""
    ax, ay = abs(x), abs(y)
    swap = ay > ax
    num = ax if swap else ay
    den = ay if swap else ax
    a = num / den if den > 0.0 else 0.0
    big = a > 0.66
    t = (a - 1.0) / (a + 1.0) if big else a
    z = t * t
    p = z * ((((_P0 * z + _P1) * z + _P2) * z + _P3) * z + _P4) / (((((z + _Q0) * z + _Q1) * z + _Q2) * z + _Q3) * z + _Q4)
    r = t * p + t
    r = _PIO4 + (r + 0.5 * _MOREBITS) if big else r
    r = _PIO2 + (_MOREBITS - r) if swap else r
    r = _PI + (2.0 * _MOREBITS - r) if x < 0.0 else r
    return math.copysign(r, y)


@njit(nogil=True, cache=True)
def _chain(V, base, nc, fi, fk, fcf, fd, endoff, home, X, Y, th, S, C):
    """The FastChain program of one pose on samples ``base .. base + nc`` into X (3, 4, CHUNK)."""
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


@njit(nogil=True, cache=True)
def _features(X, nc, pc, FB, c0):
    """ErrorFeatures rows (dx dy dz rv(3) norm reach alpha beta gamma, then |rv|) into FB[:, c0:c0+nc].

    Returns the number of samples whose rotation error is near pi (cos < -0.999).
    """
    x00, x01, x02, x03 = X[0, 0], X[0, 1], X[0, 2], X[0, 3]
    x10, x11, x12, x13 = X[1, 0], X[1, 1], X[1, 2], X[1, 3]
    x20, x21, x22, x23 = X[2, 0], X[2, 1], X[2, 2], X[2, 3]
    o0, o1, o2, o3, o4, o5 = FB[0, c0:], FB[1, c0:], FB[2, c0:], FB[3, c0:], FB[4, c0:], FB[5, c0:]
    o6, o7, o8, o9, o10, o11 = FB[6, c0:], FB[7, c0:], FB[8, c0:], FB[9, c0:], FB[10, c0:], FB[11, c0:]
    p0x, p0y, p0z, r0sq, r0 = pc[0], pc[1], pc[2], pc[3], pc[4]
    q00, q01, q02, q10, q11, q12, q20, q21, q22 = pc[5], pc[6], pc[7], pc[8], pc[9], pc[10], pc[11], pc[12], pc[13]
    ca, sa, cg, sg, b0 = pc[14], pc[15], pc[16], pc[17], pc[18]
    bad = 0
    for n in range(nc):
        px, py, pz = x03[n], x13[n], x23[n]
        dx, dy, dz = px - p0x, py - p0y, pz - p0z
        dot = (p0x * px + p0y * py + p0z * pz) - r0sq
        b1 = ca * x21[n] - sa * x22[n]
        b2 = ca * x22[n] + sa * x21[n]
        b3 = cg * x10[n] - sg * x00[n]
        b4 = cg * x00[n] + sg * x10[n]
        e00 = x00[n] * q00 + x01[n] * q01 + x02[n] * q02
        e01 = x00[n] * q10 + x01[n] * q11 + x02[n] * q12
        e02 = x00[n] * q20 + x01[n] * q21 + x02[n] * q22
        e10 = x10[n] * q00 + x11[n] * q01 + x12[n] * q02
        e11 = x10[n] * q10 + x11[n] * q11 + x12[n] * q12
        e12 = x10[n] * q20 + x11[n] * q21 + x12[n] * q22
        e20 = x20[n] * q00 + x21[n] * q01 + x22[n] * q02
        e21 = x20[n] * q10 + x21[n] * q11 + x22[n] * q12
        e22 = x20[n] * q20 + x21[n] * q21 + x22[n] * q22
        v0, v1, v2 = 0.5 * (e21 - e12), 0.5 * (e02 - e20), 0.5 * (e10 - e01)
        n2 = dx * dx + dy * dy + dz * dz
        num = 2.0 * dot + n2
        den = math.sqrt(num + r0sq) + r0
        sn = math.sqrt(v0 * v0 + v1 * v1 + v2 * v2)
        cosv = 0.5 * ((e00 + e11 + e22) - 1.0)
        bad += cosv < -0.999
        theta = _atan2(sn, cosv)
        u = theta / (sn if sn > 1e-300 else theta)
        o0[n], o1[n], o2[n] = dx, dy, dz
        o3[n], o4[n], o5[n] = v0 * u, v1 * u, v2 * u
        o6[n], o7[n] = math.sqrt(n2), num / den
        o8[n] = _atan2(b1, b2)
        o9[n] = _atan2(-x20[n], math.sqrt(b3 * b3 + b4 * b4)) - b0
        o10[n] = _atan2(b3, b4)
        o11[n] = theta
    return bad


@njit(nogil=True, cache=True, fastmath=True)
def _extrema_counts(FB, N, mx, mn, radii, aradii, cnt):
    for i in range(11):
        row = FB[i, :N]
        a, b = mx[i], mn[i]
        for n in range(N):
            a = max(a, row[n])
            b = min(b, row[n])
        mx[i], mn[i] = a, b
    for j in range(radii.size + aradii.size):
        row = FB[6, :N] if j < radii.size else FB[11, :N]
        r = radii[j] if j < radii.size else aradii[j - radii.size]
        c = 0
        for n in range(N):
            c += row[n] < r
        cnt[j] += c


@njit(nogil=True, cache=True)
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


@njit(nogil=True, cache=True, fastmath=True)
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
    M2[:] = 0.0
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


@njit(nogil=True, cache=True)
def block_kernel(V, sub, fi, fk, fcf, fd, endoff, pose_c, home, radii, aradii, lo, inv_w, nb, keep,
                 mean, M2, mx, mn, cnt, H, kept):
    """One block, every pose; sub-block moments merged in order (Chan et al., as Moments.merge)."""
    m = V.shape[1]
    P = fi.shape[0]
    X = np.empty((3, 4, CHUNK))
    Y = np.empty((3, 4, CHUNK))
    th, S, C = np.empty(CHUNK), np.empty(CHUNK), np.empty(CHUNK)
    FB = np.empty((12, sub))
    smean, sM2 = np.empty(11), np.empty((11, 11))
    mx[:] = -np.inf
    mn[:] = np.inf
    nacc = np.zeros(P, np.int64)
    for s0 in range(0, m, sub):
        N = min(sub, m - s0)
        for p in range(P):
            for c0 in range(0, N, CHUNK):
                nc = min(CHUNK, N - c0)
                _chain(V, s0 + c0, nc, fi[p], fk[p], fcf[p], fd[p], endoff[p], home, X, Y, th, S, C)
                if _features(X, nc, pose_c[p], FB, c0) > 0:
                    return False
            _extrema_counts(FB, N, mx[p], mn[p], radii, aradii, cnt[p])
            if nb >= 0:
                _hist(FB, N, lo[p], inv_w[p], nb, H[p])
            if p == 0 and s0 < keep:
                for i in range(11):
                    for n in range(min(N, keep - s0)):
                        kept[i, s0 + n] = FB[i, n]
            _moments(FB, N, smean, sM2)
            if nacc[p] == 0:
                mean[p] = smean
                M2[p] = sM2
                nacc[p] = N
            else:
                tot = nacc[p] + N
                d = smean - mean[p]
                mean[p] = mean[p] + d * (N / tot)
                w = nacc[p] * N / tot
                for i in range(11):
                    for j in range(11):
                        M2[p, i, j] = (M2[p, i, j] + sM2[i, j]) + (d[i] * d[j]) * w
                nacc[p] = tot
    return True
