"""Validation of drop-test fits: per release height and bounce, the model against the mean and
the scatter (standard deviation over the drops) of the measured intervals.

Usage: python3 benches/validate_drops.py OUT_DIR (the --out folder of bwc-identify run).
"""
import csv, statistics, sys, math, glob
for f in sorted(glob.glob(sys.argv[1] + "/*_drops.csv")):
    groups = {}
    for r in csv.DictReader(open(f)):
        groups.setdefault((float(r["h0"]), int(r["bounce_n"])), []).append((float(r["measured"]), float(r["model"])))
    dev, sd, within = [], [], 0
    for k, rows in groups.items():
        meas = [m for m, _ in rows]
        mean, s = statistics.fmean(meas), statistics.stdev(meas)
        model = rows[0][1]
        dev.append(model - mean); sd.append(s)
        within += abs(model - mean) <= s
    rms = math.sqrt(statistics.fmean([d * d for d in dev]))
    print(f"{f.split('/')[-1]:45s} groups {len(groups):3d}  rms(model - mean) {rms*1e3:6.2f} ms  median scatter (sd) {statistics.median(sd)*1e3:6.2f} ms  mean |dev| {statistics.fmean([abs(d) for d in dev])*1e3:6.2f} ms  within 1 sd: {within}/{len(groups)}")
