"""Sample the compact form of a trajectory_t (segment_* and piece_* fields) in Python, for plots:
the same arithmetic as lcmtypes/include/tdo_traj_eval.h (position, velocity, acceleration).

  import tdo_compact
  rows = tdo_compact.samples(traj)           # [t, x, y, z, vx, vy, vz, ax, ay, az] at traj.dt
  rows = tdo_compact.samples(traj, step=0.05)
"""
import bisect
import math

_GL_X = (0.1834346424956498049394761, 0.5255324099163289858177390,
         0.7966664774136267395915539, 0.9602898564975362316835609)
_GL_W = (0.3626837833783619829651504, 0.3137066458778872873379622,
         0.2223810344533744705443560, 0.1012285362903762591525314)


def _norm(a):
    return math.sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2])


def _line(q, length, s):
    d = [q[3 + k] - q[k] for k in range(3)]
    n = _norm(d)
    if s >= length:
        p = q[3:6]
    elif s <= 0.0 or n <= 0.0:
        p = q[0:3]
    else:
        p = [q[k] + d[k] * (s / n) for k in range(3)]
    t = [d[k] / n for k in range(3)] if n > 0.0 else [0.0, 0.0, 0.0]
    return list(p), t, [0.0, 0.0, 0.0]


def _arc(q, length, s):
    c = q[6:9]
    r0 = [q[k] - c[k] for k in range(3)]
    r1 = [q[3 + k] - c[k] for k in range(3)]
    r, r1n = _norm(r0), _norm(r1)
    if r <= 0.0 or r1n <= 0.0:
        return list(q[3:6] if s >= length else q[0:3]), [0.0] * 3, [0.0] * 3
    u = [x / r for x in r0]
    v = [x / r1n for x in r1]
    cs = sum(u[k] * v[k] for k in range(3))
    w = [v[k] - u[k] * cs for k in range(3)]
    wn = _norm(w)
    if wn <= 1e-300:
        return list(q[3:6] if s >= length else q[0:3]), [0.0] * 3, [0.0] * 3
    w = [x / wn for x in w]
    ang = s / r
    ca, sa = math.cos(ang), math.sin(ang)
    radial = [u[k] * ca + w[k] * sa for k in range(3)]
    if s >= length:
        p = list(q[3:6])
    elif s <= 0.0:
        p = list(q[0:3])
    else:
        p = [c[k] + radial[k] * r for k in range(3)]
    return p, [w[k] * ca - u[k] * sa for k in range(3)], [-x / r for x in radial]


def _bezier(q, length, s):
    e = [[q[3 * (i + 1) + k] - q[3 * i + k] for k in range(3)] for i in range(3)]
    h0 = [3.0 * e[0][k] for k in range(3)]
    h1 = [6.0 * (e[1][k] - e[0][k]) for k in range(3)]
    h2 = [3.0 * (e[0][k] - 2.0 * e[1][k] + e[2][k]) for k in range(3)]

    def d1(u):
        return [h0[k] + u * (h1[k] + u * h2[k]) for k in range(3)]

    def speed(u):
        return _norm(d1(u))

    def arclen(a, b):
        panels = min(64, max(1, math.ceil(abs(b - a) * 64)))
        hw = (b - a) / panels
        total = 0.0
        for p in range(panels):
            m = a + hw * (p + 0.5)
            total += 0.5 * hw * sum(_GL_W[i] * (speed(m - 0.5 * hw * _GL_X[i]) +
                                                speed(m + 0.5 * hw * _GL_X[i])) for i in range(4))
        return total

    if s <= 0.0:
        u = 0.0
    elif s >= length:
        u = 1.0
    else:
        lo, hi, u = 0.0, 1.0, s / length
        at = arclen(0.0, u)
        tol = 1e-13 * max(length, 1.0)
        for _ in range(60):
            f = at - s
            if abs(f) <= tol:
                break
            if f > 0.0:
                hi = u
            else:
                lo = u
            sp = speed(u)
            un = u - f / sp if sp > 0.0 else 0.5 * (lo + hi)
            if not lo < un < hi:
                un = 0.5 * (lo + hi)
            if not lo < un < hi:
                break
            at += arclen(u, un)
            u = un
    p = []
    for k in range(3):
        a0 = q[k] + (q[3 + k] - q[k]) * u
        a1 = q[3 + k] + (q[6 + k] - q[3 + k]) * u
        a2 = q[6 + k] + (q[9 + k] - q[6 + k]) * u
        b0, b1 = a0 + (a1 - a0) * u, a1 + (a2 - a1) * u
        p.append(q[k] if u <= 0.0 else (q[9 + k] if u >= 1.0 else b0 + (b1 - b0) * u))
    dd1 = d1(u)
    dd2 = [h1[k] + 2.0 * u * h2[k] for k in range(3)]
    sp = _norm(dd1)
    if sp <= 0.0:
        return p, [0.0] * 3, [0.0] * 3
    t = [x / sp for x in dd1]
    td2 = sum(t[k] * dd2[k] for k in range(3))
    return p, t, [(dd2[k] - t[k] * td2) / (sp * sp) for k in range(3)]


def state(traj, t):
    """[t, x, y, z, vx, vy, vz, ax, ay, az] at time t (clamped to [0, duration_s])."""
    end = not t < traj.duration_s
    t = traj.duration_s if end else max(t, 0.0)
    k = max(0, bisect.bisect_right(traj.piece_t0, t) - 1)
    tau = min(max(t - traj.piece_t0[k], 0.0), traj.piece_dur[k])
    v0, a0, j = traj.piece_v0[k], traj.piece_a0[k], traj.piece_j[k]
    s = traj.piece_s0[k] + tau * (v0 + tau * (0.5 * a0 + tau * j / 6.0))
    sd = v0 + tau * (a0 + 0.5 * tau * j)
    sdd = a0 + tau * j
    if end:
        s, sd, sdd = traj.path_length_m, 0.0, 0.0
    sd = max(sd, 0.0)
    lengths = traj.segment_length
    seg = max(0, bisect.bisect_right(traj.segment_s0, s) - 1)
    while seg > 0 and not lengths[seg] > 0.0:
        seg -= 1
    while not lengths[seg] > 0.0 and seg + 1 < traj.n_segments:
        seg += 1
    if end:
        seg = traj.n_segments - 1
        while seg > 0 and not lengths[seg] > 0.0:
            seg -= 1
    local = min(max(s - traj.segment_s0[seg], 0.0), lengths[seg])
    if end:
        local = lengths[seg]
    q = traj.segment_points[12 * seg:12 * seg + 12]
    kind = traj.segment_kind[seg]
    p, tn, kn = (_bezier if kind == 1 else _arc if kind == 2 else _line)(q, lengths[seg], local)
    return ([t] + p + [tn[k] * sd for k in range(3)] +
            [tn[k] * sdd + kn[k] * sd * sd for k in range(3)])


def samples(traj, step=None):
    """Rows at t = i * step (default the trajectory's dt) up to duration_s; [] without a profile."""
    if traj.n_pieces == 0 or traj.n_segments == 0:
        return []
    step = step or traj.dt
    n = int(math.floor(traj.duration_s / step + 1e-9)) + 1
    rows = [state(traj, i * step) for i in range(n)]
    if rows[-1][0] < traj.duration_s:
        rows.append(state(traj, traj.duration_s))
    return rows
