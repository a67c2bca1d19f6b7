#!/usr/bin/env python3
# Rotation error of each group of a merge stage by parts: for RUN
# (an output folder of tmr_mapper with plan.txt, tree.json and model 0) and
# GT (the ground-truth model), how far each group's photos sit from the
# common frame (the join's error) and from their own group's mean rotation
# (the group's own error), in degrees. Usage: group_rotations.py RUN GT
import json, math, struct, sys

def read_images(path):
    out = {}
    with open(path, 'rb') as f:
        n = struct.unpack('<Q', f.read(8))[0]
        for _ in range(n):
            iid = struct.unpack('<I', f.read(4))[0]
            q = struct.unpack('<4d', f.read(32)); f.read(24)
            f.read(4)
            name = b''
            while True:
                c = f.read(1)
                if c == b'\0': break
                name += c
            npts = struct.unpack('<Q', f.read(8))[0]
            f.seek(24 * npts, 1)
            out[name.decode()] = q
    return out
def mul(a, b):
    w1,x1,y1,z1 = a; w2,x2,y2,z2 = b
    return (w1*w2-x1*x2-y1*y2-z1*z2, w1*x2+x1*w2+y1*z2-z1*y2, w1*y2-x1*z2+y1*w2+z1*x2, w1*z2+x1*y2-y1*x2+z1*w2)
def conj(q): return (q[0], -q[1], -q[2], -q[3])
def ang(a, b): return math.degrees(2*math.acos(min(1, abs(sum(x*y for x, y in zip(a, b))))))
def mean(qs):
    s = [0,0,0,0]; ref = qs[0]
    for q in qs:
        sg = 1 if sum(x*y for x,y in zip(q, ref)) >= 0 else -1
        s = [a + sg*b for a, b in zip(s, q)]
    n = math.sqrt(sum(a*a for a in s)); return tuple(a/n for a in s)
def median(v): v = sorted(v); return v[len(v)//2]
run, gt = sys.argv[1], sys.argv[2]
m = read_images(f'{run}/0/images.bin'); g = read_images(f'{gt}/images.bin')
tree = json.load(open(f'{run}/tree.json'))
groups = {}
for line in open(f'{run}/plan.txt'):
    if line.startswith('merge.'):
        f = line.split(); ks = [int(k) for k in f[4].split('=')[1].split(',')]
        for k in ks:
            node = tree['kernels'][k]
            for n in node['kernel_images'] + [n for l in node['leaf_clusters'] for n in l]: groups[n] = int(f[0].split('.')[1])
# cam_from_world: R_m = R_g S^T  ->  S^T = R_g^T R_m ; use q = conj(q_g) * q_m
S = {n: mul(conj(g[n]), m[n]) for n in m if n in g}
Sall = mean(list(S.values()))
print('all: median', round(median([ang(Sall, s) for s in S.values()]), 4))
for G in sorted(set(groups.values())):
    Ss = [S[n] for n in S if groups.get(n) == G]
    SG = mean(Ss)
    print(f'group {G}: {len(Ss)} images, offset {ang(Sall, SG):.4f} deg, median within {median([ang(SG, s) for s in Ss]):.4f}, median vs all {median([ang(Sall, s) for s in Ss]):.4f}')
