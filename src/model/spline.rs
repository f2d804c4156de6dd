//! ROSS 2.3.0's interpolation of a tabulated coefficient, reproduced: scipy's `interp1d` for 2
//! (linear) or 3 (quadratic) points and, from 4 points on, `UnivariateSpline(x, y)` with its
//! defaults (cubic, weights 1, smoothing `s = m`, extrapolating): FITPACK's `curfit`
//! (Dierckx 1975), which adds knots where the residual is largest until the least-squares
//! spline's residual `fp` falls below `s`, then finds the smoothing parameter `p` at which
//! `fp(p) = s` by rational interpolation. The result does **not** pass through the table points.
//!
//! scipy calls it in two steps, which matter for which knots are chosen: first with room for
//! `max(m / 2, 2 k + 2)` knots and, when the knots outgrow that, once more from the knots found
//! with room for `m + k + 1` (its `_reset_nest`). Arrays are indexed from 1 below, as in
//! FITPACK, so that each step can be checked against it.

/// A coefficient as ROSS interpolates it.
#[derive(Debug, Clone, PartialEq)]
pub enum Curve {
    Constant(f64),
    /// The polynomial through 2 or 3 points, in Lagrange form (its nodes and values).
    Polynomial {
        x: Vec<f64>,
        y: Vec<f64>,
    },
    /// A cubic B-spline: knots `t` and coefficients `c` (0-based, `n` each).
    Spline {
        t: Vec<f64>,
        c: Vec<f64>,
    },
}

const K: usize = 3;

impl Curve {
    /// ROSS's curve through the table `(x, y)`, `x` increasing.
    pub fn ross(x: &[f64], y: &[f64]) -> Curve {
        match x.len() {
            0 => Curve::Constant(0.0),
            1 => Curve::Constant(y[0]),
            2 | 3 => Curve::Polynomial {
                x: x.to_vec(),
                y: y.to_vec(),
            },
            _ if y.iter().all(|v| *v == y[0]) => Curve::Constant(y[0]),
            _ => {
                let (t, c) = univariate_spline(x, y);
                Curve::Spline { t, c }
            }
        }
    }

    /// Its value at `x` (extrapolated outside the table, as ROSS does).
    pub fn at(&self, x: f64) -> f64 {
        match self {
            Curve::Constant(v) => *v,
            Curve::Polynomial { x: xs, y } => (0..xs.len())
                .map(|i| {
                    let l: f64 = (0..xs.len())
                        .filter(|&j| j != i)
                        .map(|j| (x - xs[j]) / (xs[i] - xs[j]))
                        .product();
                    y[i] * l
                })
                .sum(),
            Curve::Spline { t, c } => splev(t, c, x),
        }
    }
}

/// `splev` with `ext = 0`: the spline at `x`, the end pieces extended outside.
fn splev(t: &[f64], c: &[f64], x: f64) -> f64 {
    let n = t.len();
    let k1 = K + 1;
    let nk1 = n - k1;
    // 1-based: the interval t(l) <= x < t(l + 1), l in k1..=nk1.
    let mut l = k1;
    while l < nk1 && x >= t[l] {
        l += 1;
    }
    let h = bspl(|i| t[i - 1], K, x, l);
    (1..=k1).map(|j| c[l - k1 + j - 1] * h[j]).sum()
}

/// `fpbspl`: the `k + 1` nonzero B-splines at `t(l) <= x < t(l + 1)` (1-based `t`), in
/// `h[1..=k + 1]`.
fn bspl(t: impl Fn(usize) -> f64, k: usize, x: f64, l: usize) -> [f64; 6] {
    let mut h = [0.0; 6];
    let mut hh = [0.0; 6];
    h[1] = 1.0;
    for j in 1..=k {
        hh[1..=j].copy_from_slice(&h[1..=j]);
        h[1] = 0.0;
        for i in 1..=j {
            let (li, lj) = (l + i, l + i - j);
            if t(li) == t(lj) {
                h[i + 1] = 0.0;
                continue;
            }
            let f = hh[i] / (t(li) - t(lj));
            h[i] += f * (t(li) - x);
            h[i + 1] = f * (x - t(lj));
        }
    }
    h
}

/// `fpgivs`: the Givens rotation that zeroes `piv` against `ww` (which becomes the norm).
fn givens(piv: f64, ww: &mut f64) -> (f64, f64) {
    let store = piv.abs();
    let dd = if store >= *ww {
        store * (1.0 + (*ww / piv).powi(2)).sqrt()
    } else {
        *ww * (1.0 + (piv / *ww).powi(2)).sqrt()
    };
    let (cos, sin) = (*ww / dd, piv / dd);
    *ww = dd;
    (cos, sin)
}

/// `fprota`: applies a Givens rotation to `(a, b)`.
fn rotate(cos: f64, sin: f64, a: &mut f64, b: &mut f64) {
    let (s1, s2) = (*a, *b);
    *b = cos * s2 + sin * s1;
    *a = cos * s1 - sin * s2;
}

/// `fpback`: `c` of `a c = z`, `a` upper triangular of bandwidth `k` (rows `1..=n`, band
/// columns `1..=k`); `c` may be `z`.
fn back(a: &[Vec<f64>], z: &[f64], n: usize, k: usize, c: &mut [f64]) {
    let k1 = k - 1;
    c[n] = z[n] / a[n][1];
    if n == 1 {
        return;
    }
    let mut i = n - 1;
    for j in 2..=n {
        let mut store = z[i];
        let i1 = if j <= k1 { j - 1 } else { k1 };
        let mut m = i;
        for l in 1..=i1 {
            m += 1;
            store -= c[m] * a[i][l + 1];
        }
        c[i] = store / a[i][1];
        i = i.saturating_sub(1);
    }
}

/// The state `fpcurf` keeps between calls (scipy passes it back for its second call).
struct Fit {
    n: usize,
    t: Vec<f64>,
    c: Vec<f64>,
    fpint: Vec<f64>,
    nrdata: Vec<i64>,
    ier: i32,
}

/// UnivariateSpline(x, y): knots and coefficients, 0-based.
fn univariate_spline(x: &[f64], y: &[f64]) -> (Vec<f64>, Vec<f64>) {
    let m = x.len();
    let s = m as f64;
    let first = (m / 2).max(2 * (K + 1));
    let mut fit = Fit {
        n: 0,
        t: vec![0.0; first + 1],
        c: vec![0.0; first + 1],
        fpint: vec![0.0; first + 1],
        nrdata: vec![0; first + 1],
        ier: 0,
    };
    curfit(x, y, s, first, false, &mut fit);
    if fit.ier == 1 {
        // scipy's `_reset_nest`: the arrays grown (np.resize repeats them) to m + k + 1.
        let nest = m + K + 1;
        let grow = |v: &Vec<f64>| -> Vec<f64> {
            let old = &v[1..];
            let mut out = vec![0.0];
            out.extend((0..nest).map(|i| old[i % old.len()]));
            out
        };
        let old = &fit.nrdata[1..];
        let mut nrdata = vec![0];
        nrdata.extend((0..nest).map(|i| old[i % old.len()]));
        fit.t = grow(&fit.t);
        fit.c = grow(&fit.c);
        fit.fpint = grow(&fit.fpint);
        fit.nrdata = nrdata;
        curfit(x, y, s, nest, true, &mut fit);
    }
    let n = fit.n;
    (fit.t[1..=n].to_vec(), fit.c[1..=n].to_vec())
}

/// `fpcurf` with weights 1, `xb = x(1)`, `xe = x(m)`, `k = 3`, `tol = 0.001`, `maxit = 20`, for
/// `s > 0`: `again` is `iopt = 1` (start from the knots of the last call).
#[allow(clippy::needless_range_loop)]
fn curfit(xs: &[f64], ys: &[f64], s: f64, nest: usize, again: bool, fit: &mut Fit) {
    const TOL: f64 = 0.001;
    const MAXIT: usize = 20;
    let (k1, k2) = (K + 1, K + 2);
    let m = xs.len();
    // 1-based views.
    let x = |i: usize| xs[i - 1];
    let y = |i: usize| ys[i - 1];
    let (xb, xe) = (x(1), x(m));
    let nmin = 2 * k1;
    let acc = TOL * s;
    let nmax = m + k1;
    let t = &mut fit.t;
    let c = &mut fit.c;
    let fpint = &mut fit.fpint;
    let nrdata = &mut fit.nrdata;
    let mut n = fit.n;
    let mut ier = fit.ier;
    let mut z = vec![0.0; nest + 1];
    let mut a = vec![vec![0.0; k2 + 1]; nest + 1];
    let mut b = vec![vec![0.0; k2 + 1]; nest + 1];
    let mut g = vec![vec![0.0; k2 + 1]; nest + 1];
    let mut q = vec![[0.0; 6]; m + 1];
    let (mut fp0, mut fpold, mut nplus) = (0.0, 0.0, 0i64);
    let mut fp;
    let mut fpms = 0.0;
    let mut start_fresh = true;
    if again && n != nmin {
        fp0 = fpint[n];
        fpold = fpint[n - 1];
        nplus = nrdata[n];
        start_fresh = fp0 <= s;
    }
    if start_fresh {
        n = nmin;
        fpold = 0.0;
        nplus = 0;
        nrdata[1] = m as i64 - 2;
    }
    let mut nk1;
    // Part 1: the number and position of the knots.
    'knots: for _ in 1..=m {
        if n == nmin {
            ier = -2;
        }
        let mut nrint = n - nmin + 1;
        nk1 = n - k1;
        for j in 1..=k1 {
            t[j] = xb;
            t[n + 1 - j] = xe;
        }
        // The least-squares spline: the observation matrix by Givens rotations.
        fp = 0.0;
        for i in 1..=nk1 {
            z[i] = 0.0;
            for j in 1..=k1 {
                a[i][j] = 0.0;
            }
        }
        let mut l = k1;
        for it in 1..=m {
            let (xi, wi) = (x(it), 1.0);
            let mut yi = y(it) * wi;
            while !(xi < t[l + 1] || l == nk1) {
                l += 1;
            }
            let mut h = bspl(|i| t[i], K, xi, l);
            q[it][1..=k1].copy_from_slice(&h[1..=k1]);
            for v in &mut h[1..=k1] {
                *v *= wi;
            }
            let mut j = l - k1;
            for i in 1..=k1 {
                j += 1;
                let piv = h[i];
                if piv == 0.0 {
                    continue;
                }
                let (cos, sin) = givens(piv, &mut a[j][1]);
                rotate(cos, sin, &mut yi, &mut z[j]);
                if i == k1 {
                    break;
                }
                let mut i2 = 1;
                for i1 in i + 1..=k1 {
                    i2 += 1;
                    let (hh, aa) = (&mut h[i1], &mut a[j][i2]);
                    rotate(cos, sin, hh, aa);
                }
            }
            fp += yi * yi;
        }
        if ier == -2 {
            fp0 = fp;
        }
        fpint[n] = fp0;
        fpint[n - 1] = fpold;
        nrdata[n] = nplus;
        back(&a, &z, nk1, k1, c);
        fpms = fp - s;
        if fpms.abs() < acc {
            fit.n = n;
            fit.ier = ier;
            return;
        }
        if fpms < 0.0 {
            break 'knots;
        }
        if n == nmax {
            fit.n = n;
            fit.ier = -1;
            return;
        }
        if n == nest {
            fit.n = n;
            fit.ier = 1;
            return;
        }
        if ier != 0 {
            nplus = 1;
            ier = 0;
        } else {
            let mut npl1 = nplus * 2;
            let rn = nplus as f64;
            if fpold - fp > acc {
                // Fortran's assignment of a real to an integer truncates.
                npl1 = (rn * fpms / (fpold - fp)) as i64;
            }
            nplus = (nplus * 2).min(npl1.max(nplus / 2).max(1));
        }
        fpold = fp;
        // The residual per knot interval.
        let mut fpart = 0.0;
        let mut i = 1;
        let mut l = k2;
        let mut new = false;
        for it in 1..=m {
            if !(x(it) < t[l] || l > nk1) {
                new = true;
                l += 1;
            }
            let l0 = l - k2;
            let term: f64 = (1..=k1).map(|j| c[l0 + j] * q[it][j]).sum();
            let term = (term - y(it)).powi(2);
            fpart += term;
            if new {
                let store = term * 0.5;
                fpint[i] = fpart - store;
                i += 1;
                fpart = store;
                new = false;
            }
        }
        fpint[nrint] = fpart;
        for _ in 1..=nplus {
            add_knot(xs, t, &mut n, fpint, nrdata, &mut nrint);
            if n == nmax {
                // The knots as for interpolation (k odd: at the data points).
                let mk1 = m - k1;
                let (mut i, mut j) = (k2, K / 2 + 2);
                for _ in 0..mk1 {
                    t[i] = x(j);
                    i += 1;
                    j += 1;
                }
                continue 'knots;
            }
            if n == nest {
                continue 'knots;
            }
        }
    }
    if ier == -2 {
        fit.n = n;
        fit.ier = ier;
        return;
    }
    // Part 2: the smoothing spline, p with f(p) = s.
    nk1 = n - k1;
    disc(t, n, k2, &mut b);
    let (mut p1, mut f1, mut p3, mut f3) = (0.0, fp0 - s, -1.0, fpms);
    let mut p = (1..=nk1).map(|i| a[i][1]).sum::<f64>();
    p = nk1 as f64 / p;
    let (mut ich1, mut ich3) = (false, false);
    let n8 = n - nmin;
    for iter in 1..=MAXIT {
        let pinv = 1.0 / p;
        for i in 1..=nk1 {
            c[i] = z[i];
            g[i][k2] = 0.0;
            for j in 1..=k1 {
                g[i][j] = a[i][j];
            }
        }
        for it in 1..=n8 {
            let mut h = [0.0; 7];
            for i in 1..=k2 {
                h[i] = b[it][i] * pinv;
            }
            let mut yi = 0.0;
            for j in it..=nk1 {
                let piv = h[1];
                let (cos, sin) = givens(piv, &mut g[j][1]);
                rotate(cos, sin, &mut yi, &mut c[j]);
                if j == nk1 {
                    break;
                }
                let i2 = if j > n8 { nk1 - j } else { k1 };
                for i in 1..=i2 {
                    let i1 = i + 1;
                    let (hh, gg) = (&mut h[i1], &mut g[j][i1]);
                    rotate(cos, sin, hh, gg);
                    h[i] = h[i1];
                }
                h[i2 + 1] = 0.0;
            }
        }
        let zc = c.clone();
        back(&g, &zc, nk1, k2, c);
        fp = 0.0;
        let mut l = k2;
        for it in 1..=m {
            if !(x(it) < t[l] || l > nk1) {
                l += 1;
            }
            let l0 = l - k2;
            let term: f64 = (1..=k1).map(|j| c[l0 + j] * q[it][j]).sum();
            fp += (term - y(it)).powi(2);
        }
        fpms = fp - s;
        if fpms.abs() < acc {
            break;
        }
        if iter == MAXIT {
            ier = 3;
            break;
        }
        let (p2, f2) = (p, fpms);
        if !ich3 {
            if f2 - f3 <= acc {
                // p too large.
                p3 = p2;
                f3 = f2;
                p *= 0.04;
                if p <= p1 {
                    p = p1 * 0.9 + p2 * 0.1;
                }
                continue;
            }
            if f2 < 0.0 {
                ich3 = true;
            }
        }
        if !ich1 {
            if f1 - f2 <= acc {
                // p too small.
                p1 = p2;
                f1 = f2;
                p /= 0.04;
                if p3 < 0.0 {
                    continue;
                }
                if p >= p3 {
                    p = p2 * 0.1 + p3 * 0.9;
                }
                continue;
            }
            if f2 > 0.0 {
                ich1 = true;
            }
        }
        if f2 >= f1 || f2 <= f3 {
            ier = 2;
            break;
        }
        p = rati(&mut p1, &mut f1, p2, f2, &mut p3, &mut f3);
    }
    fit.n = n;
    fit.ier = ier;
}

/// `fpknot`: a knot added inside the interval of largest residual, at its middle data point.
fn add_knot(
    xs: &[f64],
    t: &mut [f64],
    n: &mut usize,
    fpint: &mut [f64],
    nrdata: &mut [i64],
    nrint: &mut usize,
) {
    let k = (*n - *nrint - 1) / 2;
    let mut fpmax = 0.0;
    let mut jbegin = 1i64;
    let (mut number, mut maxpt, mut maxbeg) = (1usize, 0i64, 1i64);
    for j in 1..=*nrint {
        let jpoint = nrdata[j];
        if !(fpmax >= fpint[j] || jpoint == 0) {
            fpmax = fpint[j];
            number = j;
            maxpt = jpoint;
            maxbeg = jbegin;
        }
        jbegin += jpoint + 1;
    }
    let ihalf = maxpt / 2 + 1;
    let nrx = (maxbeg + ihalf) as usize;
    let next = number + 1;
    if next <= *nrint {
        for j in next..=*nrint {
            let jj = next + *nrint - j;
            fpint[jj + 1] = fpint[jj];
            nrdata[jj + 1] = nrdata[jj];
            let jk = jj + k;
            t[jk + 1] = t[jk];
        }
    }
    nrdata[number] = ihalf - 1;
    nrdata[next] = maxpt - ihalf;
    let am = maxpt as f64;
    fpint[number] = fpmax * nrdata[number] as f64 / am;
    fpint[next] = fpmax * nrdata[next] as f64 / am;
    t[next + k] = xs[nrx - 1];
    *n += 1;
    *nrint += 1;
}

/// `fpdisc`: the jumps of the k-th derivative of the B-splines at the interior knots.
#[allow(clippy::explicit_counter_loop)]
fn disc(t: &[f64], n: usize, k2: usize, b: &mut [Vec<f64>]) {
    let k1 = k2 - 1;
    let k = k1 - 1;
    let nk1 = n - k1;
    let nrint = nk1 - k;
    let fac = nrint as f64 / (t[nk1 + 1] - t[k1]);
    let mut h = [0.0; 13];
    for l in k2..=nk1 {
        let lmk = l - k1;
        for j in 1..=k1 {
            let (ik, lj) = (j + k1, l + j);
            let lk = lj - k2;
            h[j] = t[l] - t[lk];
            h[ik] = t[l] - t[lj];
        }
        let mut lp = lmk;
        for j in 1..=k2 {
            let mut jk = j;
            let mut prod = h[j];
            for _ in 1..=k {
                jk += 1;
                prod = prod * h[jk] * fac;
            }
            let lk = lp + k1;
            b[lmk][j] = (t[lk] - t[lp]) / prod;
            lp += 1;
        }
    }
}

/// `fprati`: the zero of the rational `(u p + v) / (p + w)` through three points; the bracket
/// `(p1, f1 > 0)`, `(p3, f3 < 0)` updated.
fn rati(p1: &mut f64, f1: &mut f64, p2: f64, f2: f64, p3: &mut f64, f3: &mut f64) -> f64 {
    let p = if *p3 > 0.0 {
        let h1 = *f1 * (f2 - *f3);
        let h2 = f2 * (*f3 - *f1);
        let h3 = *f3 * (*f1 - f2);
        -(*p1 * p2 * h3 + p2 * *p3 * h1 + *p3 * *p1 * h2) / (*p1 * h1 + p2 * h2 + *p3 * h3)
    } else {
        (*p1 * (*f1 - *f3) * f2 - p2 * (f2 - *f3) * *f1) / ((*f1 - f2) * *f3)
    };
    if f2 < 0.0 {
        *p3 = p2;
        *f3 = f2;
    } else {
        *p1 = p2;
        *f1 = f2;
    }
    p
}

#[cfg(test)]
mod tests;
