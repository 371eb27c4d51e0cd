"""Numbers of errata E5.11-E5.13 and E6.6-E6.7 (thesis ch. 5-6), recomputed
in plain floating point from the definitions, independent of the library.

Run: python3 docs/derivations/wrist_errata_ch5_6.py (standard library only).
The Rust tests named in docs/ERRATA.md check the same numbers.
"""
import math

PHI = math.radians(16.0)
CP, SP = math.cos(PHI), math.sin(PHI)


def rz(a):
    s, c = math.sin(a), math.cos(a)
    return [[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]]


def rx(a):
    s, c = math.sin(a), math.cos(a)
    return [[1.0, 0.0, 0.0], [0.0, c, -s], [0.0, s, c]]


def mul(a, b):
    return [[sum(a[i][k] * b[k][j] for k in range(3)) for j in range(3)] for i in range(3)]


def chain(t1, t4, t3):
    """Eq. (5.4) in the order of the matrices of eq. (5.5) (E5.1)."""
    return mul(mul(mul(mul(rz(t1), rx(PHI)), rz(t4)), rx(-PHI)), rz(t3))


def theta4_physical(t1, t3):
    """Eq. (5.10)/(5.12), the '-' root."""
    s1, c1, s3, c3 = math.sin(t1), math.cos(t1), math.sin(t3), math.cos(t3)
    a = s1 * c3 + c1 * s3 * CP * CP
    b = CP * math.cos(t1 + t3)
    c = -c1 * s3 * SP * SP
    return math.atan2(b, a) - math.acos(c / math.hypot(a, b))


def grid(n=72):
    for i in range(n):
        for j in range(n):
            yield -math.pi + 2 * math.pi * i / n, -math.pi + 2 * math.pi * j / n


# E5.11: t12 of eq. (5.5).
worst = (0.0, None)
for t1, t3 in grid():
    t4 = theta4_physical(t1, t3)
    s1, c1, s3, c3, s4, c4 = (math.sin(t1), math.cos(t1), math.sin(t3), math.cos(t3),
                              math.sin(t4), math.cos(t4))
    head = s1 * s4 * s3 * CP - c1 * c4 * s3 - c1 * s4 * c3 * CP - s1 * c4 * c3 * CP ** 2
    r = chain(t1, t4, t3)
    assert abs(head - s1 * c3 * SP ** 2 - r[0][1]) < 1e-14
    e = abs(head - s1 * s3 * SP ** 2 - r[0][1])
    if e > worst[0]:
        worst = (e, (t1, t3))
print(f"E5.11 printed t12 off by {worst[0]:.5f} at theta1, theta3 = {worst[1]}; "
      f"sqrt(2) sin^2 phi = {math.sqrt(2) * SP ** 2:.5f}")

# E5.12: t31, t32 as repeated in section 5.3.
w31 = w32 = (0.0, None)
for t1, t3 in grid():
    t4 = theta4_physical(t1, t3)
    s3, c3, s4, c4 = math.sin(t3), math.cos(t3), math.sin(t4), math.cos(t4)
    r = chain(t1, t4, t3)
    p31 = s3 * CP * SP + s4 * c3 * SP - c4 * s3 * SP * CP
    p32 = s4 * s3 * SP - c3 * CP * SP + c4 * c3 * SP * CP
    if abs(p31 - r[2][0]) > w31[0]:
        w31 = (abs(p31 - r[2][0]), (t1, t3, t4))
    if abs(p32 - r[2][1]) > w32[0]:
        w32 = (abs(p32 - r[2][1]), (t1, t3, t4))
print(f"E5.12 printed t31 off by {w31[0]:.4f} at {w31[1]} (2 sin 2phi = {2 * math.sin(2 * PHI):.4f}); "
      f"t32 by {w32[0]:.4f} at {w32[1]} (2 sin phi = {2 * SP:.4f})")

# E5.13: the order of the inverses in eq. (5.29), at one configuration.
t1, t3 = -0.5, -1.0
u = t1 + t3
tphi = math.tan(PHI)
omega = tphi * math.cos(u / 2) / (1 + tphi ** 2 * math.sin(u / 2) ** 2)
jc = [[-0.5, 0.5], [-omega, -omega]]
beta = -2 * math.atan(tphi * math.sin(u / 2))
alpha = (t3 - t1) / 2 + math.pi
sa, ca, sb, cb = math.sin(alpha), math.cos(alpha), math.sin(beta), math.cos(beta)
cd = math.sqrt(1 - (ca * sb) ** 2)
q = cb ** 2 + (sa * sb) ** 2
j2 = [[-sa * sb / cd, ca * cb / cd], [ca * sb * cb / q, sa / q]]


def t(m):
    return [[m[0][0], m[1][0]], [m[0][1], m[1][1]]]


def inv(m):
    d = m[0][0] * m[1][1] - m[0][1] * m[1][0]
    return [[m[1][1] / d, -m[0][1] / d], [-m[1][0] / d, m[0][0] / d]]


def app(m, v):
    return [m[0][0] * v[0] + m[0][1] * v[1], m[1][0] * v[0] + m[1][1] * v[1]]


tau13 = [1.0, 0.0]
right = app(inv(t(j2)), app(inv(t(jc)), tau13))
printed = app(inv(t(jc)), app(inv(t(j2)), tau13))
back = app(t(jc), app(t(j2), right))
print(f"E5.13 at theta1 = {t1}, theta3 = {t3}, tau13 = {tau13}: (J2^T)^-1 (Jc^T)^-1 -> {right}, "
      f"maps back to {back}; printed order -> {printed}")

# E6.6: dtheta3/dtheta2 of the inner universal joint, by finite differences
# of eq. (5.1), at the workspace boundary beta = 2 phi.
beta = 2 * PHI


def theta2(t3):
    return math.atan2(math.cos(beta) * math.sin(t3), math.cos(t3))


h = 1e-6
ratios = []
for k in range(181):
    t3 = -math.pi / 2 + math.pi * k / 180 + 1e-4
    ratios.append(2 * h / (theta2(t3 + h) - theta2(t3 - h)))
print(f"E6.6 dtheta3/dtheta2 at beta = 2 phi: [{min(ratios):.4f}, {max(ratios):.4f}] "
      f"(cos 2phi = {math.cos(beta):.4f}, 1/cos 2phi = {1 / math.cos(beta):.4f})")

# E6.7: springs in series.
kr, ke = 1000.0, 1000.0
print(f"E6.7 K_r = K_e = 1000 N m/rad: series stiffness {kr * ke / (kr + ke):.0f}, "
      f"printed K_r + K_e = {kr + ke:.0f}")
