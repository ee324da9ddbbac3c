import sys, json, numpy as np
for path in sys.argv[1:]:
    d = np.load(path); T, TA, TB = d["T"], d["TA"], d["TB"]; us = 1e6 / float(d["hz"]); kinds = d["kinds"]
    info = json.loads(str(d["info"]))
    n = T.shape[0]
    print(path, f"threads {info['threads']}, {info['material']}, {n} steps x {info['elements']} el., load {info['load_before']:.1f}-{info['load_after']:.1f}, CPU {info['cpu']:.1f} s, wall {info['wall']:.1f} s, Fx {info['Fx']:.6f}")
    dA = (TA[:, :, 1] - TA[:, :, 0]) * us; dB = (TB[:, :, 1] - TB[:, :, 0]) * us
    for name, sel, D in (("even chunks", kinds == 0, dA), ("contact", kinds == 1, dA), ("groups", slice(None), dB)):
        X = D[:, sel]
        print(f"  {name:12s} per task p5 {np.percentile(X, 5):7.1f} us, p25 {np.percentile(X, 25):7.1f}, median {np.median(X):7.1f}; sum of per-task p5 {np.percentile(X, 5, axis=0).sum():8.1f} us")
    if info["threads"] > 1:
        for name, TT in (("phase 1", TA), ("phase 2", TB)):
            th = TT[:, :, 2]
            both = (th == 0).any(1) & (th == 1).any(1)
            same = (th[1:] == th[:-1])[both[1:] & both[:-1]]
            print(f"  {name}: both threads work in {both.mean():.0%} of the steps; in consecutive such steps a task runs on the same thread as in the step before {same.mean():.1%} of the time")
        # phase wall (median) in steps where both threads worked in both phases
        b1 = ((TA[:, :, 2] == 0).any(1) & (TA[:, :, 2] == 1).any(1)) & ((TB[:, :, 2] == 0).any(1) & (TB[:, :, 2] == 1).any(1))
        for nm, a, b in (("phase 1", 0, 1), ("serial 1", 1, 2), ("phase 2", 2, 3), ("serial 2", 3, 4)):
            w = (T[:, b] - T[:, a]) * us
            print(f"  {nm}: p5 {np.percentile(w[b1], 5) if b1.any() else np.nan:8.1f} us, median {np.median(w[b1]) if b1.any() else np.nan:8.1f} (steps with both threads in both phases: {b1.sum()})")
        for nm, TT, a, b in (("phase 1", TA, 0, 1), ("phase 2", TB, 2, 3)):
            ends = [np.where(TT[:, :, 2] == t, TT[:, :, 1], 0).max(1) for t in (0, 1)]
            gap = np.abs(ends[0] - ends[1]) * us
            print(f"  {nm}: |end of thread 0 - end of thread 1| p5/median/p75 {np.percentile(gap[b1], 5):.1f} / {np.median(gap[b1]):.1f} / {np.percentile(gap[b1], 75):.1f} us")
    else:
        for nm, a, b in (("phase 1", 0, 1), ("serial 1", 1, 2), ("phase 2", 2, 3), ("serial 2", 3, 4)):
            w = (T[:, b] - T[:, a]) * us
            print(f"  {nm}: p5 {np.percentile(w, 5):8.1f} us, median {np.median(w):8.1f}")
