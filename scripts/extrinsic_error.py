"""Signed error of a result file's extrinsic against a truth file's, per camera axis.

The validation scripts' tables read it (association_validation.sh, association_minutes.sh):
error = result - truth, the rotation as the rotation vector of R_result R_truth^T.
"""
import math


def _matrix(v):  # Rodrigues
    a = math.sqrt(sum(x * x for x in v))
    if a < 1e-12:
        return [[1.0 if i == j else 0.0 for j in range(3)] for i in range(3)]
    k = [x / a for x in v]
    c, s = math.cos(a), math.sin(a)
    K = [[0, -k[2], k[1]], [k[2], 0, -k[0]], [-k[1], k[0], 0]]
    return [[c * (i == j) + s * K[i][j] + (1 - c) * k[i] * k[j] for j in range(3)] for i in range(3)]


def signed_error(result, truth):
    """(angle rad, rotation vector rad about camera x, y, z, translation cm along x, y, z)."""
    A, B = _matrix(result["rotation_vector"]), _matrix(truth["rotation_vector"])
    E = [[sum(A[i][k] * B[j][k] for k in range(3)) for j in range(3)] for i in range(3)]  # A B^T
    a = math.acos(max(-1.0, min(1.0, (E[0][0] + E[1][1] + E[2][2] - 1) / 2)))
    w = [E[2][1] - E[1][2], E[0][2] - E[2][0], E[1][0] - E[0][1]]
    w = [x / (2 * math.sin(a)) * a for x in w] if a > 1e-12 else [0.0] * 3
    dt = [100 * (x - y) for x, y in zip(result["translation"], truth["translation"])]
    return a, w, dt
