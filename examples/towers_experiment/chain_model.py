import math, sys

def softness(hz, zeta, h):
    w = 2*math.pi*hz; a1 = 2*zeta + h*w; a2 = h*w*a1; a3 = 1/(1+a2)
    return (w/a1, a2*a3, a3)

def run(N, mode=0, bscale=1.0, record=False, shock=False, linear=False, beta=1.0, iters=1, riters=1, switch=0, alpha=1.0, seconds=10.0, substeps=4, hz=30.0, zeta=10.0, slop=0.001, g=9.81, verbose=False, order='redblack', extra=None):
    dt = 1/60; h = dt/substeps
    sc = softness(hz, zeta, h); ss = softness(2*hz, zeta, h)
    if extra == 'allstatic': sc = ss
    # positions: gap C_j of contact j (negative = penetration); contact 0 floor-box0
    # track y of boxes: y_i bottom height
    y = [float(i) for i in range(N)]  # bottom of box i; contact j between box j-1 (or floor) and box j
    v = [0.0]*N
    lam = [0.0]*N   # per contact j: impulse on box j (up) and box j-1 (down)
    m = [1.0]*N
    meff = [1.0] + [0.5]*(N-1)
    soft = [ss] + [sc]*(N-1)
    if order == 'redblack':
        seq = list(range(0, N, 2)) + list(range(1, N, 2))
    elif order == 'up':
        seq = list(range(N))
    else:
        seq = list(range(N-1, -1, -1))
    steps = int(seconds/dt)
    hist = []
    mode_final = mode
    for step in range(steps):
        mode = 0 if step < switch else mode_final
        if mode in (1, 4): L = lam[:]
        elif mode in (7, 8): L = [(N-j)*g*h for j in range(N)]
        if mode == 8: lam = L[:]
        elif mode == 5: L = [beta*x for x in lam]
        elif step == 0: L = [0.0]*N
        for s in range(substeps):
            v = [x - g*h for x in v]
            # warm start
            for j in range(N):
                v[j] += lam[j]/m[j]
                if j > 0: v[j-1] -= lam[j]/m[j-1]
            def gap(j):
                return y[j] - (y[j-1] + 1.0 if j > 0 else 0.0)
            def vrel(j):
                return v[j] - (v[j-1] if j > 0 else 0.0)
            def apply(j, d):
                v[j] += d/m[j]
                if j > 0: v[j-1] -= d/m[j-1]
            # biased pass
            for j in seq * iters:
                C = gap(j)
                br, ms, isc = soft[j]
                if C > 0 and not linear:
                    bias = C/h; msc = 1.0; leak = 0.0
                else:
                    dps = C + slop
                    bias = bscale*br*min(dps, 0.0); msc = ms
                    leak = isc if (dps < 0 or linear) else 0.0
                if mode == 4:
                    M = max(meff[j], L[j]/(g*h))
                    hz_j = 2*hz if j == 0 else hz
                    w = 2*math.pi*hz_j; k = M*w*w; c = 2*zeta*M*w
                    gam = 1/(h*(c + h*k)); beta = h*k/(c + h*k)
                    msoft = 1/(1/meff[j] + gam)
                    if C > 0:
                        d = -meff[j]*(vrel(j) + C/h)
                    elif C + slop >= 0:
                        d = -msoft*vrel(j)
                    else:
                        d = -msoft*(vrel(j) + beta/h*(C + slop) + gam*lam[j])
                    new = max(lam[j] + d, 0.0)
                    apply(j, new - lam[j]); lam[j] = new
                    continue
                if mode == 0: lk = lam[j]
                elif mode in (1, 3, 5, 7, 8): lk = lam[j] - L[j]
                elif mode == 6: lk = (1-beta)*lam[j]
                else: lk = 0.0
                d = -meff[j]*msc*(vrel(j) + bias) - leak*lk
                new = lam[j] + d if linear else max(lam[j] + d, 0.0)
                apply(j, new - lam[j]); lam[j] = new
            if shock:
                for j in range(N):
                    C = gap(j)
                    if C > 0: continue
                    br = soft[j][0]
                    bias = br*min(C + slop, 0.0)
                    need = -(vrel(j) + bias)
                    if need > 0:
                        v[j] += need
                        if record: lam[j] += need*m[j]
            y = [a + h*b for a, b in zip(y, v)]
            # relax
            for j in seq * riters:
                C = gap(j)
                bias = C/h if (C > 0 and not linear) else 0.0
                d = -meff[j]*(vrel(j) + bias)
                new = lam[j] + d if linear else max(lam[j] + d, 0.0)
                apply(j, new - lam[j]); lam[j] = new
        if mode == 3: L = [l + alpha*(x - l) for l, x in zip(L, lam)]
        gaps = [y[j] - (y[j-1] + 1.0 if j > 0 else 0.0) for j in range(N)]
        hist.append((step, min(gaps), max(abs(x) for x in v)))
        if verbose and step % 15 == 0:
            print(f"t {step/60:.2f} min gap {min(gaps)*1e3:.3f} mm  vmax {max(abs(x) for x in v):.4f}  gaps {[round(x*1e3,2) for x in gaps]} v {[round(x,3) for x in v]}")
    gaps = [y[j] - (y[j-1] + 1.0 if j > 0 else 0.0) for j in range(N)]
    return min(h_[1] for h_ in hist), max(h_[2] for h_ in hist[-60:]), gaps

if __name__ == '__main__':
    mode = int(sys.argv[1]); N = int(sys.argv[2])
    pen, vmax, gaps = run(N, mode, seconds=float(sys.argv[3]) if len(sys.argv) > 3 else 5.0, verbose=True)
    print("worst pen mm", -pen*1e3, "vmax last 1s", vmax)
    print([round(x*1e3,2) for x in gaps])
