#!/usr/bin/env python3
# Usage: bench/registration_score_poses.py <capture with gt/> <simtree register output>
# Scores simtree register's poses.json against gt/scan_poses.json: for each registered view, the
# rotation error and the displacement of points on the tree's axis (foot, 1.8 m, 3.5 m up),
# relative to the anchor.
import json, math, sys
def M(a): return [a[0:4], a[4:8], a[8:12], a[12:16]]
def mul(A, B): return [[sum(A[i][k]*B[k][j] for k in range(4)) for j in range(4)] for i in range(4)]
def inv(A):
    R = [[A[j][i] for j in range(3)] for i in range(3)]
    t = [-sum(R[i][k]*A[k][3] for k in range(3)) for i in range(3)]
    return [R[0]+[t[0]], R[1]+[t[1]], R[2]+[t[2]], [0, 0, 0, 1]]
def app(A, p): return [sum(A[i][k]*p[k] for k in range(3)) + A[i][3] for i in range(3)]
cap, reg = sys.argv[1], sys.argv[2]
gt = {v['name']: M(v['world_from_camera']) for v in json.load(open(cap + '/gt/scan_poses.json'))['views']}
est = json.load(open(reg + '/poses.json'))
a = est['anchor']
F = {v['name']: M(v['frame_from_camera']) for v in est['views'] if v['registered']}
Wa, Fa = gt[a], F[a]
worst_rot = worst_mm = 0
for name, Fi in F.items():
    Wi = gt[name]
    E = mul(inv(mul(inv(Wa), Wi)), mul(inv(Fa), Fi))
    c = max(-1, min(1, (E[0][0] + E[1][1] + E[2][2] - 1) / 2))
    rot = math.degrees(math.acos(c))
    d = []
    for X in ([0, 0, 0], [0, 0, 1.8], [0, 0, 3.5]):
        ci = app(inv(Wi), X)
        e = app(mul(inv(Fa), Fi), ci)
        t = app(inv(Wa), X)
        d.append(1e3 * math.dist(e, t))
    worst_rot, worst_mm = max(worst_rot, rot), max(worst_mm, max(d))
    print(f"{name}: rot {rot:.2f} deg, axis points {d[0]:.0f}/{d[1]:.0f}/{d[2]:.0f} mm")
print(f"{cap}: {len(F)} of {len(est['views'])} registered; worst rot {worst_rot:.2f} deg, worst {worst_mm:.0f} mm")
