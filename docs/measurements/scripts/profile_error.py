# Profile error between two free-surface CSVs (x_mm,z_mm): RMS of the gap and the area between them over
# the common x-range, piecewise-linear profiles sampled at 20,000 points (reproduces the study report's
# 1.44 mm / 46 mm2 and 2.62 mm / 88 mm2 on the seed-1 s = 1 GranuDrum surfaces). Usage: profile_error.py A.csv B.csv
import sys
def rd(f):
    pts=[]
    for l in open(f):
        if l.startswith('#') or not l.strip(): continue
        a=l.strip().split(',')
        try: pts.append((float(a[0]),float(a[1])))
        except ValueError: pass
    pts=[p for p in pts if p[1]==p[1]]
    pts.sort(); return pts
def interp(p,x):
    for i in range(1,len(p)):
        if p[i][0]>=x:
            x0,y0=p[i-1]; x1,y1=p[i]
            return y0+(y1-y0)*(x-x0)/(x1-x0) if x1>x0 else y1
    return p[-1][1]
a=rd(sys.argv[1]); b=rd(sys.argv[2])
lo=max(a[0][0],b[0][0]); hi=min(a[-1][0],b[-1][0]); n=20000
s2=0; s1=0
for k in range(n):
    x=lo+(hi-lo)*(k+0.5)/n; d=interp(a,x)-interp(b,x)
    s2+=d*d; s1+=abs(d)
L=hi-lo
print('RMS %.3f mm  area %.1f mm2  range %.1f..%.1f'%((s2/n)**0.5, s1/n*L, lo, hi))
