"""Derivation notes for the DAUJ wrist forward kinematics (thesis ch. 5).

Compares the product orders of eq. (5.4) with the entries printed under
eq. (5.5), and derives the constraint, the theta4 branches and the
inverse kinematics. Run: python3 docs/derivations/wrist_fk.py (needs sympy).
"""
import sympy as sp

t1, t3, t4, ph, d, g = sp.symbols("theta1 theta3 theta4 phi delta gamma", real=True)
C1, S1, C3, S3, C4, S4 = sp.cos(t1), sp.sin(t1), sp.cos(t3), sp.sin(t3), sp.cos(t4), sp.sin(t4)
Cp, Sp = sp.cos(ph), sp.sin(ph)


def Rz(a):
    return sp.Matrix([[sp.cos(a), -sp.sin(a), 0], [sp.sin(a), sp.cos(a), 0], [0, 0, 1]])


def Rx(a):
    return sp.Matrix([[1, 0, 0], [0, sp.cos(a), -sp.sin(a)], [0, sp.sin(a), sp.cos(a)]])


def Ry(a):
    return sp.Matrix([[sp.cos(a), 0, sp.sin(a)], [0, 1, 0], [-sp.sin(a), 0, sp.cos(a)]])


printed = {
    (0, 0): C1*C4*C3 - S1*S4*C3*Cp - C1*S4*S3*Cp - S1*C4*S3*Cp**2,
    (1, 0): S1*C4*C3 + C1*S4*C3*Cp - S1*S4*S3*Cp + C1*C4*S3*Cp**2 + C1*S3*Sp**2,
    (2, 0): -S3*Cp*Sp + S4*C3*Sp + C4*S3*Sp*Cp,
    (0, 1): S1*S4*S3*Cp - C1*C4*S3 - C1*S4*C3*Cp - S1*C4*C3*Cp**2 - S1*S3*Sp**2,
    (1, 1): C1*C4*C3*Cp**2 + C1*C3*Sp**2 - S1*C4*S3 - C1*S4*S3*Cp - S1*S4*C3*Cp,
    (2, 1): -S4*S3*Sp - C3*Cp*Sp + C4*C3*Sp*Cp,
    (0, 2): S1*Cp*Sp - C1*S4*Sp - S1*C4*Cp*Sp,
    (1, 2): C1*C4*Cp*Sp - S1*S4*Sp - C1*Cp*Sp,
}

orders = {
    "Rz1 Rx(-phi) Rz4 Rx(phi) Rz3 (first line of 5.4)": Rz(t1)*Rx(-ph)*Rz(t4)*Rx(ph)*Rz(t3),
    "Rz1 Rx(+phi) Rz4 Rx(-phi) Rz3 (matrices of 5.5)": Rz(t1)*Rx(ph)*Rz(t4)*Rx(-ph)*Rz(t3),
}
for name, R in orders.items():
    print(name)
    for (i, j), e in printed.items():
        diff = sp.simplify(sp.expand_trig(R[i, j] - e))
        print(f"  t{i+1}{j+1}: printed - derived = {diff}")
    print("  t33 =", sp.simplify(R[2, 2]))

R = orders["Rz1 Rx(+phi) Rz4 Rx(-phi) Rz3 (matrices of 5.5)"]
print("t21 collected in C4, S4:", sp.collect(sp.expand(R[1, 0]), [C4, S4]))
print("orthogonality R R^T - I:", sp.simplify(R*R.T - sp.eye(3)))
print("target (5.6) Ry(d) Rx(g) =", Ry(d)*Rx(g))
