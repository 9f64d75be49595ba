"""Compares the two pictures of each renamed VTK test (run.sh): VTK mapper vs ours.

Per test: mean |difference| per channel (0..255), the percentage of pixels differing by more
than 16 levels ("big"), and how much of each picture differs from its background (fgO: VTK,
fgA: ours). MATCH: mean <= 2 and big <= 1%; CLOSE: mean <= 6 and big <= 8%; BLANK: ours covers
less than a fifth of what VTK covers; DIFF otherwise.
Usage: compare.py <work dir of run.sh>
"""
import sys, os, numpy as np, vtk
from vtk.util import numpy_support as ns
def load(p):
    r=vtk.vtkPNGReader(); r.SetFileName(p); r.Update(); im=r.GetOutput()
    d=im.GetDimensions(); a=ns.vtk_to_numpy(im.GetPointData().GetScalars())
    return a.reshape(d[1],d[0],-1)[:,:,:3].astype(float)
rows=[]
for n in open(sys.argv[1]+'/tests.txt').read().split():
    o=sys.argv[1]+'/out/orig/%s.png'%n; a=sys.argv[1]+'/out/accel/%s.png'%n
    if not os.path.exists(o): rows.append((n,'NO-ORIG','')); continue
    if not os.path.exists(a): rows.append((n,'NO-ACCEL','')); continue
    A=load(o); B=load(a)
    if A.shape!=B.shape: rows.append((n,'SIZE',str(A.shape)+str(B.shape))); continue
    d=np.abs(A-B); mean=d.mean(); big=(d.max(axis=2)>16).mean()*100
    bg=B.reshape(-1,3)[0]; varA=(np.abs(A-A.reshape(-1,3)[0]).max(axis=2)>8).mean()*100; varB=(np.abs(B-bg).max(axis=2)>8).mean()*100
    cls='MATCH' if mean<=2 and big<=1 else ('CLOSE' if mean<=6 and big<=8 else 'DIFF')
    if varA>1 and varB<0.2*varA: cls='BLANK'
    rows.append((n,cls,'mean=%.2f big=%.1f%% fgO=%.1f%% fgA=%.1f%%'%(mean,big,varA,varB)))
from collections import Counter
for r in rows: print('%-52s %-8s %s'%r)
print(Counter(r[1] for r in rows))
