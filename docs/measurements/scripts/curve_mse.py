# Mean squared pressure misfit [MPa^2] of simulated pressure_volume.csv folders against a target curve
# (target's volumes, linear interpolation): the Table-1-style replicates of docs/measurements/README.md.
# Usage (run where out_15_02/target_pressure_volume.csv is): curve_mse.py 'rep_1.5_0.2_*' ...
import csv,glob,sys,bisect
def rd(f):
    rows=[l for l in open(f) if not l.startswith('#')]
    r=list(csv.reader(rows))[1:]
    return [(float(a),float(b)) for a,b in r]
t=rd('out_15_02/target_pressure_volume.csv')
def mse(c):
    xs=[a for a,b in c][::-1]; ys=[b for a,b in c][::-1]
    s=0;n=0
    for x,y in t:
        if x<xs[0] or x>xs[-1]: continue
        i=bisect.bisect_left(xs,x)
        v=ys[0] if i==0 else ys[i-1]+(ys[i]-ys[i-1])*(x-xs[i-1])/(xs[i]-xs[i-1])
        s+=(v-y)**2;n+=1
    return s/n
for pat in sys.argv[1:]:
    v=[mse(rd(f+'/pressure_volume.csv')) for f in sorted(glob.glob(pat))]
    print(pat, ' '.join('%.5f'%x for x in v))
